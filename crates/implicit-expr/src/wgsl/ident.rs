//! WGSL identifiers: the checks that keep generated names from clashing with the language.
//!
//! A name is accepted when it is an ASCII WGSL identifier (`[A-Za-z_][A-Za-z0-9_]*`, not
//! `_`, not starting with `__`), is not a keyword or reserved word (a shader-creation error
//! in WGSL), and is not a predeclared identifier: WGSL lets a module-scope declaration
//! shadow a built-in function or type, but a generated function named `sin` would hide the
//! built-in `sin` from the whole module, the interval library included.

/// WGSL keywords and reserved words (WGSL specification, "Keyword and Token Summary"),
/// with the words the naga front end also reserves.
#[rustfmt::skip]
const RESERVED: &[&str] = &[
    // Keywords.
    "alias", "break", "case", "const", "const_assert", "continue", "continuing", "default",
    "diagnostic", "discard", "else", "enable", "false", "fn", "for", "if", "let", "loop",
    "override", "requires", "return", "struct", "switch", "true", "var", "while",
    // Reserved words.
    "NULL", "Self", "abstract", "active", "alignas", "alignof", "as", "asm", "asm_fragment",
    "async", "attribute", "auto", "await", "become", "binding_array", "cast", "catch", "class",
    "co_await", "co_return", "co_yield", "coherent", "column_major", "common", "compile",
    "compile_fragment", "concept", "const_cast", "consteval", "constexpr", "constinit", "crate",
    "debugger", "decltype", "delete", "demote", "demote_to_helper", "do", "dynamic_cast",
    "enum", "explicit", "export", "extends", "extern", "external", "fallthrough", "filter",
    "final", "finally", "friend", "from", "fxgroup", "get", "goto", "groupshared", "highp",
    "impl", "implements", "import", "inline", "instanceof", "interface", "layout", "lowp",
    "macro", "macro_rules", "match", "mediump", "meta", "mod", "module", "move", "mut",
    "mutable", "namespace", "new", "nil", "noexcept", "noinline", "nointerpolation",
    "non_coherent", "noncoherent", "noperspective", "null", "nullptr", "of", "operator",
    "package", "packoffset", "partition", "pass", "patch", "pixelfragment", "precise",
    "precision", "premerge", "priv", "protected", "pub", "public", "readonly", "ref",
    "regardless", "register", "reinterpret_cast", "require", "resource", "restrict", "self",
    "set", "shared", "sizeof", "smooth", "snorm", "static", "static_assert", "static_cast",
    "std", "subroutine", "super", "target", "template", "this", "thread_local", "throw",
    "trait", "try", "type", "typedef", "typeid", "typename", "typeof", "union", "unless",
    "unorm", "unsafe", "unsized", "use", "using", "varying", "virtual", "volatile", "wgsl",
    "where", "with", "writeonly", "yield",
];

/// Predeclared WGSL identifiers: types and type generators, enumerants, built-in functions
/// (and the 64-bit types and names some implementations add).
#[rustfmt::skip]
const PREDECLARED: &[&str] = &[
    // Types and type generators.
    "bool", "i32", "u32", "f32", "f16", "i64", "u64", "f64", "array", "atomic", "ptr", "vec2",
    "vec3", "vec4", "vec2i", "vec3i", "vec4i", "vec2u", "vec3u", "vec4u", "vec2f", "vec3f",
    "vec4f", "vec2h", "vec3h", "vec4h", "mat2x2", "mat2x3", "mat2x4", "mat3x2", "mat3x3",
    "mat3x4", "mat4x2", "mat4x3", "mat4x4", "mat2x2f", "mat2x3f", "mat2x4f", "mat3x2f",
    "mat3x3f", "mat3x4f", "mat4x2f", "mat4x3f", "mat4x4f", "mat2x2h", "mat2x3h", "mat2x4h",
    "mat3x2h", "mat3x3h", "mat3x4h", "mat4x2h", "mat4x3h", "mat4x4h", "sampler",
    "sampler_comparison", "texture_1d", "texture_2d", "texture_2d_array", "texture_3d",
    "texture_cube", "texture_cube_array", "texture_multisampled_2d",
    "texture_depth_multisampled_2d", "texture_external", "texture_storage_1d",
    "texture_storage_2d", "texture_storage_2d_array", "texture_storage_3d", "texture_depth_2d",
    "texture_depth_2d_array", "texture_depth_cube", "texture_depth_cube_array",
    // Enumerants: access modes, address spaces, texel formats.
    "read", "write", "read_write", "function", "private", "workgroup", "uniform", "storage",
    "handle", "push_constant", "rgba8unorm", "rgba8snorm", "rgba8uint", "rgba8sint",
    "rgba16unorm", "rgba16snorm", "rgba16uint", "rgba16sint", "rgba16float", "rg8unorm",
    "rg8snorm", "rg8uint", "rg8sint", "rg16unorm", "rg16snorm", "rg16uint", "rg16sint",
    "rg16float", "r32uint", "r32sint", "r32float", "rg32uint", "rg32sint", "rg32float",
    "rgba32uint", "rgba32sint", "rgba32float", "bgra8unorm", "r8unorm", "r8snorm", "r8uint",
    "r8sint", "r16unorm", "r16snorm", "r16uint", "r16sint", "r16float", "rgb10a2unorm",
    "rgb10a2uint", "rg11b10ufloat", "r64uint", "r64sint",
    // Built-in functions.
    "bitcast", "all", "any", "select", "arrayLength", "abs", "acos", "acosh", "asin", "asinh",
    "atan", "atanh", "atan2", "ceil", "clamp", "cos", "cosh", "countLeadingZeros",
    "countOneBits", "countTrailingZeros", "cross", "degrees", "determinant", "distance", "dot",
    "dot4U8Packed", "dot4I8Packed", "exp", "exp2", "extractBits", "faceForward",
    "firstLeadingBit", "firstTrailingBit", "floor", "fma", "fract", "frexp", "insertBits",
    "inverseSqrt", "ldexp", "length", "log", "log2", "max", "min", "mix", "modf", "normalize",
    "pow", "quantizeToF16", "radians", "reflect", "refract", "reverseBits", "round", "saturate",
    "sign", "sin", "sinh", "smoothstep", "sqrt", "step", "tan", "tanh", "transpose", "trunc",
    "dpdx", "dpdxCoarse", "dpdxFine", "dpdy", "dpdyCoarse", "dpdyFine", "fwidth",
    "fwidthCoarse", "fwidthFine", "textureDimensions", "textureGather", "textureGatherCompare",
    "textureLoad", "textureNumLayers", "textureNumLevels", "textureNumSamples", "textureSample",
    "textureSampleBias", "textureSampleCompare", "textureSampleCompareLevel",
    "textureSampleGrad", "textureSampleLevel", "textureSampleBaseClampToEdge", "textureStore",
    "atomicLoad", "atomicStore", "atomicAdd", "atomicSub", "atomicMax", "atomicMin",
    "atomicAnd", "atomicOr", "atomicXor", "atomicExchange", "atomicCompareExchangeWeak",
    "pack4x8snorm", "pack4x8unorm", "pack4xI8", "pack4xU8", "pack4xI8Clamp", "pack4xU8Clamp",
    "pack2x16snorm", "pack2x16unorm", "pack2x16float", "unpack4x8snorm", "unpack4x8unorm",
    "unpack4xI8", "unpack4xU8", "unpack2x16snorm", "unpack2x16unorm", "unpack2x16float",
    "storageBarrier", "textureBarrier", "workgroupBarrier", "workgroupUniformLoad",
    "subgroupAdd", "subgroupExclusiveAdd", "subgroupInclusiveAdd", "subgroupAll", "subgroupAnd",
    "subgroupAny", "subgroupBallot", "subgroupBroadcast", "subgroupBroadcastFirst",
    "subgroupElect", "subgroupMax", "subgroupMin", "subgroupMul", "subgroupExclusiveMul",
    "subgroupInclusiveMul", "subgroupOr", "subgroupShuffle", "subgroupShuffleDown",
    "subgroupShuffleUp", "subgroupShuffleXor", "subgroupXor", "quadBroadcast",
    "quadSwapDiagonal", "quadSwapX", "quadSwapY",
];

/// Why `name` cannot be a WGSL identifier, or `None` when it can.
///
/// Checks the syntax and the keyword, reserved and predeclared words only; the callers add
/// the names that the generated code reserves for itself.
pub(crate) fn problem(name: &str) -> Option<String> {
    let mut chars = name.chars();
    let Some(first) = chars.next() else {
        return Some("an identifier cannot be empty".into());
    };
    if !(first.is_ascii_alphabetic() || first == '_') {
        return Some(format!(
            "'{name}' is not a WGSL identifier: it must start with an ASCII letter or '_'"
        ));
    }
    if let Some(c) = name
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || *c == '_'))
    {
        return Some(format!(
            "'{name}' is not a WGSL identifier: {c:?} is not an ASCII letter, digit or '_'"
        ));
    }
    if name == "_" {
        return Some("'_' alone is not a WGSL identifier".into());
    }
    if name.starts_with("__") {
        return Some(format!(
            "'{name}' is not a WGSL identifier: names starting with '__' are reserved"
        ));
    }
    if RESERVED.contains(&name) {
        return Some(format!("'{name}' is a WGSL keyword or reserved word"));
    }
    if PREDECLARED.contains(&name) {
        return Some(format!(
            "'{name}' is a predeclared WGSL name (a built-in type or function); declaring it \
             would hide the built-in"
        ));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn syntax() {
        for ok in ["f", "sphere", "_a", "a_", "A1", "g_dg", "x", "p0", "a__b"] {
            assert_eq!(problem(ok), None, "{ok}");
        }
        for bad in [
            "", "1a", "a-b", "a b", "_", "__a", "é", "a.b", "fn", "let", "sin", "f32",
        ] {
            assert!(problem(bad).is_some(), "{bad}");
        }
    }

    #[test]
    fn lists_have_no_duplicates() {
        let mut all: Vec<&str> = RESERVED.iter().chain(PREDECLARED).copied().collect();
        let n = all.len();
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), n);
    }
}
