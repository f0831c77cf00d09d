//! Surfaces of a scene file: a formula, a catalog name or a `.vm` file with its parameters,
//! bounds and material, built in its own context and placed in the scene's.

use std::io::Read;
use std::path::{Path, PathBuf};

use implicit_expr::parse::{is_valid_param, parse, suggest};
use implicit_expr::vm::import_vm;
use implicit_expr::{Context, NodeId, catalog};

use super::animation::TIME;
use super::diagnostics::{Doc, fmt3};
use super::material::Material;
use super::schema::{RawMaterial, RawSurface};
use super::transform::Affine;
use super::transform::local_coordinates;
use crate::error::Error;
use crate::ibox::{IBox, ival};

/// Largest `.vm` file read.
const MAX_VM_BYTES: u64 = 256 << 20;

pub(super) fn material(doc: &Doc<'_>, path: &str, m: &RawMaterial) -> Result<Material, Error> {
    let mut out = Material::default();
    if let Some(c) = m.color {
        out.color = doc.color(&format!("{path}.color"), c)?;
    }
    if let Some(v) = m.specular {
        out.specular = doc.unit(&format!("{path}.specular"), v)? as f32;
    }
    if let Some(v) = m.shininess {
        let p = format!("{path}.shininess");
        let v = doc.positive(&p, v)?;
        if v > 1e4 {
            return Err(doc.err(&p, format!("must be at most 10000, got {v}")));
        }
        out.shininess = v as f32;
    }
    Ok(out)
}

/// The text of a formula with its error span marked, for messages.
pub(super) fn formula_snippet(formula: &str, e: &implicit_expr::Error) -> String {
    let implicit_expr::Error::Syntax { span, .. } = e else {
        return String::new();
    };
    let floor = |mut i: usize| {
        i = i.min(formula.len());
        while !formula.is_char_boundary(i) {
            i -= 1;
        }
        i
    };
    let start = floor(span.start);
    let end = floor(span.end.max(start));
    let line_start = formula[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = formula[start..]
        .find('\n')
        .map_or(formula.len(), |i| start + i);
    let end = end.min(line_end);
    const CONTEXT: usize = 40;
    let before: Vec<char> = formula[line_start..start].chars().collect();
    let cut = before.len().saturating_sub(CONTEXT);
    let mut text: String = if cut > 0 { "…".into() } else { String::new() };
    text.extend(&before[cut..]);
    let pad = text.chars().count();
    let marked = formula[start..end].chars().count().max(1);
    text.push_str(&formula[start..end]);
    let after: Vec<char> = formula[end..line_end].chars().collect();
    text.extend(after.iter().take(CONTEXT));
    if after.len() > CONTEXT {
        text.push('…');
    }
    format!(
        "\n    {text}\n    {}{}",
        " ".repeat(pad),
        "^".repeat(marked)
    )
}

/// The parts of a surface before it is placed in the scene's context.
pub(super) struct Built {
    pub(super) name: String,
    /// The surface in its own context (with its parameters as variables) and its root.
    pub(super) ctx: Context,
    pub(super) root: NodeId,
    /// The value of every variable slot from 3 on.
    pub(super) params: Vec<f64>,
    pub(super) bounds: [[f64; 3]; 2],
    pub(super) clip: bool,
}

/// The path of a file a scene names: relative paths against `base` (the scene file's
/// folder) where there is one.
pub(super) fn resolve(file: &str, base: Option<&Path>) -> PathBuf {
    match base {
        Some(b) if Path::new(file).is_relative() => b.join(file),
        _ => PathBuf::from(file),
    }
}

pub(super) fn read_vm(
    doc: &Doc<'_>,
    path: &str,
    file: &str,
    base: Option<&Path>,
) -> Result<String, Error> {
    let full = resolve(file, base);
    let fail = |m: String| doc.err(path, format!("cannot read '{}': {m}", full.display()));
    let meta = std::fs::metadata(&full).map_err(|e| fail(e.to_string()))?;
    if !meta.is_file() {
        return Err(fail("not a regular file".into()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(&full)
        .and_then(|f| f.take(MAX_VM_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| fail(e.to_string()))?;
    if bytes.len() as u64 > MAX_VM_BYTES {
        return Err(fail(format!("larger than {MAX_VM_BYTES} bytes")));
    }
    String::from_utf8(bytes).map_err(|_| fail("not UTF-8 text".into()))
}

/// Builds surface `i` of the file; `time` is the frame time `t` of an animation, which its
/// formula may use (unless a parameter of its own is called `t`).
pub(super) fn build_surface(
    doc: &Doc<'_>,
    i: usize,
    s: &RawSurface,
    base: Option<&Path>,
    time: Option<f64>,
) -> Result<Built, Error> {
    let at = |field: &str| format!("surfaces[{i}].{field}");
    let sources: Vec<&str> = [
        ("formula", s.formula.is_some()),
        ("catalog", s.catalog.is_some()),
        ("vm", s.vm.is_some()),
    ]
    .iter()
    .filter(|x| x.1)
    .map(|x| x.0)
    .collect();
    if sources.len() != 1 {
        let found = if sources.is_empty() {
            "none".to_string()
        } else {
            format!("'{}'", sources.join("' and '"))
        };
        return Err(doc.err(
            &format!("surfaces[{i}]"),
            format!("give exactly one of 'formula', 'catalog' or 'vm' (found {found})"),
        ));
    }
    for (k, v) in &s.params {
        doc.finite(&at(&format!("params.{k}")), *v)?;
    }
    let mut ctx = Context::new();
    let (root, name, default_bounds, default_clip) = if let Some(cat) = &s.catalog {
        let surf = catalog::get(cat).map_err(|e| doc.err(&at("catalog"), e))?;
        let names = surf.param_names();
        for k in s.params.keys() {
            if !names.contains(&k.as_str()) {
                let msg = if names.is_empty() {
                    format!("catalog surface '{cat}' has no parameters")
                } else {
                    let hint = suggest::did_you_mean(k, names.iter().copied())
                        .map(|h| format!("; {h}"))
                        .unwrap_or_default();
                    format!(
                        "unknown parameter '{k}' of catalog surface '{cat}'{hint} (parameters: {})",
                        names.join(", ")
                    )
                };
                return Err(doc.err(&at(&format!("params.{k}")), msg));
            }
        }
        let root = surf
            .build(&mut ctx)
            .map_err(|e| doc.err(&at("catalog"), e))?;
        (
            root,
            surf.name.to_string(),
            Some(surf.bounds),
            surf.is_clipped(),
        )
    } else if let Some(formula) = &s.formula {
        for k in s.params.keys() {
            let problem = if ["x", "y", "z"].contains(&k.as_str()) {
                "is a coordinate"
            } else if !is_valid_param(k) {
                "is not a parameter name (letters, digits and '_', not a function or constant)"
            } else {
                continue;
            };
            return Err(doc.err(&at(&format!("params.{k}")), format!("'{k}' {problem}")));
        }
        let mut names: Vec<&str> = s.params.keys().map(String::as_str).collect();
        if time.is_some() && !s.params.contains_key(TIME) {
            names.push(TIME);
        }
        let root = parse(&mut ctx, formula, &names)
            .map_err(|e| doc.err_detail(&at("formula"), &e, &formula_snippet(formula, &e)))?;
        (root, format!("surface-{i}"), None, false)
    } else {
        let file = s.vm.as_deref().unwrap_or_default();
        if let Some(k) = s.params.keys().next() {
            return Err(doc.err(
                &at(&format!("params.{k}")),
                "a .vm surface has no parameters",
            ));
        }
        let text = read_vm(doc, &at("vm"), file, base)?;
        let root = import_vm(&mut ctx, &text)
            .map_err(|e| doc.err(&at("vm"), format!("in '{file}': {e}")))?;
        let stem = Path::new(file).file_stem().map_or_else(
            || format!("surface-{i}"),
            |s| s.to_string_lossy().into_owned(),
        );
        (root, stem, None, false)
    };
    let bounds = match (s.bounds, default_bounds) {
        (Some([lo, hi]), _) => {
            doc.vec3(&at("bounds"), lo)?;
            doc.vec3(&at("bounds"), hi)?;
            if (0..3).any(|k| lo[k] >= hi[k]) {
                return Err(doc.err(
                    &at("bounds"),
                    format!(
                        "the first corner must be below the second on every axis, got {} and {}",
                        fmt3(&lo),
                        fmt3(&hi)
                    ),
                ));
            }
            [lo, hi]
        }
        (None, Some((lo, hi))) => [lo, hi],
        (None, None) => {
            return Err(doc.err(
                &format!("surfaces[{i}]"),
                format!(
                    "missing 'bounds' (required for a {} surface): \
                     bounds = [[x0, y0, z0], [x1, y1, z1]]",
                    sources[0]
                ),
            ));
        }
    };
    let mut params = Vec::new();
    for k in 3..ctx.var_count() {
        let var = &ctx.var_names()[k];
        let v = match &s.catalog {
            Some(cat) => s.params.get(var).copied().or_else(|| {
                catalog::get(cat)
                    .ok()
                    .and_then(|c| c.params.iter().find(|p| p.0 == var).map(|p| p.1))
            }),
            None => s.params.get(var).copied().or(time.filter(|_| var == TIME)),
        };
        let Some(v) = v else {
            return Err(doc.err(&at("params"), format!("no value for parameter '{var}'")));
        };
        params.push(v);
    }
    Ok(Built {
        name: s.name.clone().unwrap_or(name),
        ctx,
        root,
        params,
        bounds,
        clip: s.clip.unwrap_or(default_clip),
    })
}

/// `max(f, b)` with the exact box function `b` of `[lo, hi]`.
pub(super) fn clip_to_box(
    ctx: &mut Context,
    f: NodeId,
    [lo, hi]: &[[f64; 3]; 2],
) -> Result<NodeId, Error> {
    let vars = [ctx.x(), ctx.y(), ctx.z()];
    let mut out = f;
    for k in 0..3 {
        let l = ctx.constant(lo[k])?;
        let h = ctx.constant(hi[k])?;
        let below = ctx.sub(l, vars[k]);
        let above = ctx.sub(vars[k], h);
        out = ctx.max(out, below);
        out = ctx.max(out, above);
    }
    Ok(out)
}

/// Places a built surface in the scene context: parameters bound, clipped, transformed.
pub(super) fn place(
    doc: &Doc<'_>,
    i: usize,
    b: &mut Built,
    aff: &Affine,
    geo: &mut Context,
) -> Result<(NodeId, IBox), Error> {
    let path = format!("surfaces[{i}]");
    let wrap = |e: Error| doc.err(&path, e);
    let mut root = b.root;
    if b.clip {
        root = clip_to_box(&mut b.ctx, root, &b.bounds).map_err(wrap)?;
    }
    let mut map = local_coordinates(geo, aff).map_err(wrap)?.to_vec();
    for &v in &b.params {
        map.push(geo.constant(v).map_err(|e| wrap(e.into()))?);
    }
    if map.len() != b.ctx.var_count() {
        return Err(doc.err(&path, "internal error: variable slots do not match"));
    }
    let node = geo.copy_graph(&b.ctx, root, |_, v| map[v.index()]);
    let [lo, hi] = b.bounds;
    let local: IBox = std::array::from_fn(|k| ival(lo[k], hi[k]));
    let world = if aff.is_identity() {
        Some(local)
    } else {
        aff.world_bounds(&local)
    };
    let world = world.ok_or_else(|| {
        doc.err(
            &format!("{path}.transform"),
            "the transformed bounds are not finite (or the map is nearly singular)",
        )
    })?;
    Ok((node, world))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snippet_marks_the_span() {
        let e = parse(&mut Context::new(), "x + sine(y)", &[]).unwrap_err();
        assert_eq!(
            formula_snippet("x + sine(y)", &e),
            "\n    x + sine(y)\n        ^^^^"
        );
    }
}
