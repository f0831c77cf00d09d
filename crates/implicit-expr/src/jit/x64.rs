//! The few x86-64 instructions the compiled tapes use, encoded into a byte buffer: SSE2
//! on `xmm0`–`xmm7` (no REX prefix needed; `xmm8`, the NaN mask, only in the three
//! instructions that clear, grow and read it), loads and stores at `rsp`, `rdi`, `rsi`,
//! `rdx` plus a displacement or at a label of the constant pool (RIP-relative, patched when
//! the pool is placed), and the handful of integer instructions of the prologue, the
//! epilogue and the choice bytes.

/// An SSE register, `xmm0` to `xmm7`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) struct Xmm(pub(super) u8);

/// A memory operand.
#[derive(Copy, Clone, Debug)]
pub(super) enum Mem {
    /// `[rsp + disp]`.
    Stack(i32),
    /// `[rdi + disp]`: the variables.
    Vars(i32),
    /// `[rdx + disp]`: the output.
    Out(i32),
    /// `[rip + …]`: byte `offset` of the constant pool.
    Pool(u32),
}

/// A packed (`66`) or scalar double (`F2`) SSE operation.
#[derive(Copy, Clone, Debug)]
pub(super) enum Sse {
    /// `movupd` (load form).
    MovUpd,
    /// `movapd` (register form).
    MovApd,
    /// `movsd`: from memory, the low lane with the high one cleared; between registers, the
    /// low lane only.
    MovSd,
    /// `addpd`.
    AddPd,
    /// `mulpd`.
    MulPd,
    /// `minpd`.
    MinPd,
    /// `maxpd`.
    MaxPd,
    /// `andpd`.
    AndPd,
    /// `andnpd` (`dst = !dst & src`).
    AndNPd,
    /// `cmpeqpd` (`cmppd` with the quiet equality predicate).
    CmpEqPd,
    /// `orpd`.
    OrPd,
    /// `xorpd`.
    XorPd,
    /// `unpcklpd`.
    UnpckLPd,
    /// `unpckhpd`.
    UnpckHPd,
    /// `paddq`.
    PAddQ,
    /// `mulsd`.
    MulSd,
    /// `sqrtsd`.
    SqrtSd,
    /// `minsd`.
    MinSd,
    /// `maxsd`.
    MaxSd,
}

impl Sse {
    /// The immediate byte that follows the operands, for the comparisons.
    fn imm(self) -> Option<u8> {
        matches!(self, Sse::CmpEqPd).then_some(0)
    }

    fn encoding(self) -> (u8, u8) {
        match self {
            Sse::MovUpd => (0x66, 0x10),
            Sse::MovApd => (0x66, 0x28),
            Sse::MovSd => (0xF2, 0x10),
            Sse::AddPd => (0x66, 0x58),
            Sse::MulPd => (0x66, 0x59),
            Sse::MinPd => (0x66, 0x5D),
            Sse::MaxPd => (0x66, 0x5F),
            Sse::AndPd => (0x66, 0x54),
            Sse::AndNPd => (0x66, 0x55),
            Sse::CmpEqPd => (0x66, 0xC2),
            Sse::OrPd => (0x66, 0x56),
            Sse::XorPd => (0x66, 0x57),
            Sse::UnpckLPd => (0x66, 0x14),
            Sse::UnpckHPd => (0x66, 0x15),
            Sse::PAddQ => (0x66, 0xD4),
            Sse::MulSd => (0xF2, 0x59),
            Sse::SqrtSd => (0xF2, 0x51),
            Sse::MinSd => (0xF2, 0x5D),
            Sse::MaxSd => (0xF2, 0x5F),
        }
    }
}

/// Comparison predicates of `cmppd` / `cmpsd`: `Lt` and `Le` signal (a NaN operand raises
/// the invalid flag), `Unord` and `Neq` do not.
#[derive(Copy, Clone, Debug)]
pub(super) enum Cmp {
    /// `a < b`.
    Lt = 1,
    /// `a ≤ b`.
    Le = 2,
    /// `a` or `b` is NaN.
    Unord = 3,
    /// `a ≠ b`.
    Neq = 4,
}

/// A RIP-relative displacement to patch: where it is, where its instruction ends, and the
/// pool byte it addresses.
struct Fixup {
    at: usize,
    end: usize,
    pool: u32,
}

/// The code being assembled.
#[derive(Default)]
pub(super) struct Asm {
    code: Vec<u8>,
    fixups: Vec<Fixup>,
}

const RSP: u8 = 4;
const RDI: u8 = 7;
const RDX: u8 = 2;

impl Asm {
    /// Appends `b`; a fixed number of bytes, so that the copy is a few stores.
    #[inline(always)]
    fn put<const N: usize>(&mut self, b: [u8; N]) {
        self.code.extend_from_slice(&b);
    }

    fn disp32(&mut self, d: i32) {
        self.put(d.to_le_bytes());
    }

    /// `head` (prefix and opcode bytes), then ModRM (and SIB, displacement) for register
    /// field `reg` and memory operand `m`; `imm` is the immediate byte that follows, if
    /// any (a RIP-relative displacement counts from the instruction's end). Each form is
    /// written as one fixed run of bytes: a code is assembled from thousands of these.
    #[inline(always)]
    fn mem_form<const H: usize>(&mut self, head: [u8; H], reg: u8, m: Mem, imm: Option<u8>) {
        let reg = (reg & 7) << 3;
        self.put(head);
        // `[base + disp8]` (mod 01) where the displacement fits, else `[base + disp32]`;
        // `rsp` as a base needs a SIB byte.
        match m {
            Mem::Stack(d) | Mem::Vars(d) | Mem::Out(d) => {
                let base = match m {
                    Mem::Stack(_) => RSP,
                    Mem::Vars(_) => RDI,
                    _ => RDX,
                };
                match (i8::try_from(d), base == RSP) {
                    (Ok(d8), true) => self.put([0x40 | reg | base, 0x24, d8 as u8]),
                    (Ok(d8), false) => self.put([0x40 | reg | base, d8 as u8]),
                    (Err(_), true) => {
                        let [a, b, c, e] = d.to_le_bytes();
                        self.put([0x80 | reg | base, 0x24, a, b, c, e]);
                    }
                    (Err(_), false) => {
                        let [a, b, c, e] = d.to_le_bytes();
                        self.put([0x80 | reg | base, a, b, c, e]);
                    }
                }
            }
            Mem::Pool(p) => {
                let at = self.code.len() + 1;
                self.put([reg | 0x05, 0, 0, 0, 0]);
                self.fixups.push(Fixup {
                    at,
                    end: at + 4 + usize::from(imm.is_some()),
                    pool: p,
                });
            }
        }
        if let Some(i) = imm {
            self.put([i]);
        }
    }

    /// `op dst, src` between registers.
    pub(super) fn rr(&mut self, op: Sse, dst: Xmm, src: Xmm) {
        let (p, o) = op.encoding();
        self.put([p, 0x0F, o, 0xC0 | (dst.0 << 3) | src.0]);
        if let Some(i) = op.imm() {
            self.put([i]);
        }
    }

    /// `op dst, [m]`.
    pub(super) fn rm(&mut self, op: Sse, dst: Xmm, m: Mem) {
        let (p, o) = op.encoding();
        self.mem_form([p, 0x0F, o], dst.0, m, op.imm());
    }

    /// `movupd [m], src`.
    pub(super) fn store(&mut self, m: Mem, src: Xmm) {
        self.mem_form([0x66, 0x0F, 0x11], src.0, m, None);
    }

    /// `shufpd x, x, 1`: the two lanes swapped.
    pub(super) fn swap(&mut self, x: Xmm) {
        self.put([0x66, 0x0F, 0xC6, 0xC0 | (x.0 << 3) | x.0, 1]);
    }

    /// `cmppd dst, src, pred` (both lanes).
    pub(super) fn cmppd(&mut self, dst: Xmm, src: Xmm, pred: Cmp) {
        self.put([0x66, 0x0F, 0xC2, 0xC0 | (dst.0 << 3) | src.0, pred as u8]);
    }

    /// `cmpsd dst, src, pred` (low lane).
    pub(super) fn cmpsd(&mut self, dst: Xmm, src: Xmm, pred: Cmp) {
        self.put([0xF2, 0x0F, 0xC2, 0xC0 | (dst.0 << 3) | src.0, pred as u8]);
    }

    /// `movmskpd eax, x`.
    pub(super) fn movmskpd_eax(&mut self, x: Xmm) {
        self.put([0x66, 0x0F, 0x50, 0xC0 | x.0]);
    }

    /// `movmskpd ecx, x`.
    pub(super) fn movmskpd_ecx(&mut self, x: Xmm) {
        self.put([0x66, 0x0F, 0x50, 0xC8 | x.0]);
    }

    /// `xorpd xmm8, xmm8`: the NaN mask cleared.
    pub(super) fn clear_nan_mask(&mut self) {
        self.put([0x66, 0x45, 0x0F, 0x57, 0xC0]);
    }

    /// `orpd xmm8, x`: the NaN mask gains the lanes set in `x`.
    pub(super) fn or_nan_mask(&mut self, x: Xmm) {
        self.put([0x66, 0x44, 0x0F, 0x56, 0xC0 | x.0]);
    }

    /// `eax` = 1 where a lane of the NaN mask `xmm8` is set, else 0 (`movmskpd eax, xmm8;
    /// add eax, 3; shr eax, 2`).
    pub(super) fn nan_mask_eax(&mut self) {
        self.put([
            0x66, 0x41, 0x0F, 0x50, 0xC0, 0x83, 0xC0, 0x03, 0xC1, 0xE8, 0x02,
        ]);
    }

    /// `movzx eax, byte [rcx + rax + disp]`: a byte of the table `rcx` points at.
    pub(super) fn load_table_byte(&mut self, disp: i8) {
        self.put([0x0F, 0xB6, 0x44, 0x01, disp as u8]);
    }

    /// `mov byte [rsi + disp], al`: a choice byte.
    pub(super) fn store_choice(&mut self, disp: i32) {
        self.put([0x88, 0x86]);
        self.disp32(disp);
    }

    /// `lea rcx, [rip + …]`: `rcx` at pool byte `pool`.
    pub(super) fn lea_rcx_pool(&mut self, pool: u32) {
        self.mem_form([0x48, 0x8D], 1, Mem::Pool(pool), None);
    }

    /// `sub rsp, n`.
    pub(super) fn sub_rsp(&mut self, n: i32) {
        self.put([0x48, 0x81, 0xEC]);
        self.disp32(n);
    }

    /// `add rsp, n`.
    pub(super) fn add_rsp(&mut self, n: i32) {
        self.put([0x48, 0x81, 0xC4]);
        self.disp32(n);
    }

    /// `ldmxcsr [m]`.
    pub(super) fn ldmxcsr(&mut self, m: Mem) {
        self.mem_form([0x0F, 0xAE], 2, m, None);
    }

    /// `stmxcsr [m]`.
    pub(super) fn stmxcsr(&mut self, m: Mem) {
        self.mem_form([0x0F, 0xAE], 3, m, None);
    }

    /// `eax = (eax & 1) | ((ecx & 3) << 1)`.
    pub(super) fn merge_flags(&mut self) {
        // and eax, 1; and ecx, 3; shl ecx, 1; or eax, ecx
        self.put([0x83, 0xE0, 0x01, 0x83, 0xE1, 0x03, 0xD1, 0xE1, 0x09, 0xC8]);
    }

    /// `call [rip + …]`: a call to the address at pool byte `pool`.
    pub(super) fn call_pool(&mut self, pool: u32) {
        self.mem_form([0xFF], 2, Mem::Pool(pool), None);
    }

    /// Makes room for `n` more bytes of code.
    pub(super) fn reserve(&mut self, n: usize) {
        self.code.reserve(n);
    }

    /// The number of bytes assembled so far.
    pub(super) fn len(&self) -> usize {
        self.code.len()
    }

    /// `ret`.
    pub(super) fn ret(&mut self) {
        self.put([0xC3]);
    }

    /// Empties the buffers (keeping their memory) for the next code.
    pub(super) fn clear(&mut self) {
        self.code.clear();
        self.fixups.clear();
    }

    /// The code followed by the pool (at a 16-byte aligned offset), with every
    /// RIP-relative displacement patched.
    pub(super) fn finish(&mut self, pool: &[u8]) -> &[u8] {
        while !self.code.len().is_multiple_of(16) {
            // int3: never reached.
            self.code.push(0xCC);
        }
        let base = self.code.len();
        for f in &self.fixups {
            let target = base + f.pool as usize;
            let d = target as i64 - f.end as i64;
            let d = i32::try_from(d).expect("code and pool within 2 GiB");
            self.code[f.at..f.at + 4].copy_from_slice(&d.to_le_bytes());
        }
        self.code.extend_from_slice(pool);
        &self.code
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodings_match_the_manual() {
        let mut a = Asm::default();
        a.rr(Sse::AddPd, Xmm(0), Xmm(1)); // addpd xmm0, xmm1
        a.rm(Sse::MovUpd, Xmm(2), Mem::Stack(0x20)); // movupd xmm2, [rsp+0x20]
        a.store(Mem::Out(0), Xmm(3)); // movupd [rdx+0], xmm3
        a.rm(Sse::MovUpd, Xmm(1), Mem::Vars(16)); // movupd xmm1, [rdi+16]
        a.swap(Xmm(5)); // shufpd xmm5, xmm5, 1
        a.cmppd(Xmm(3), Xmm(4), Cmp::Le); // cmplepd xmm3, xmm4
        a.movmskpd_eax(Xmm(3));
        a.load_table_byte(4);
        a.store_choice(7);
        a.rm(Sse::MovUpd, Xmm(0), Mem::Stack(0x200)); // movupd xmm0, [rsp+0x200]
        a.cmppd(Xmm(1), Xmm(2), Cmp::Unord); // cmpunordpd xmm1, xmm2
        a.clear_nan_mask(); // xorpd xmm8, xmm8
        a.or_nan_mask(Xmm(1)); // orpd xmm8, xmm1
        a.nan_mask_eax(); // movmskpd eax, xmm8; add eax, 3; shr eax, 2
        let code = a.finish(&[]).to_vec();
        let want: &[u8] = &[
            0x66, 0x0F, 0x58, 0xC1, //
            0x66, 0x0F, 0x10, 0x54, 0x24, 0x20, //
            0x66, 0x0F, 0x11, 0x5A, 0, //
            0x66, 0x0F, 0x10, 0x4F, 16, //
            0x66, 0x0F, 0xC6, 0xED, 1, //
            0x66, 0x0F, 0xC2, 0xDC, 2, //
            0x66, 0x0F, 0x50, 0xC3, //
            0x0F, 0xB6, 0x44, 0x01, 4, //
            0x88, 0x86, 7, 0, 0, 0, //
            0x66, 0x0F, 0x10, 0x84, 0x24, 0, 2, 0, 0, //
            0x66, 0x0F, 0xC2, 0xCA, 3, //
            0x66, 0x45, 0x0F, 0x57, 0xC0, //
            0x66, 0x44, 0x0F, 0x56, 0xC1, //
            0x66, 0x41, 0x0F, 0x50, 0xC0, 0x83, 0xC0, 0x03, 0xC1, 0xE8, 0x02,
        ];
        assert_eq!(&code[..want.len()], want);
    }

    #[test]
    fn rip_relative_displacements_point_at_the_pool() {
        let mut a = Asm::default();
        a.rm(Sse::XorPd, Xmm(0), Mem::Pool(16)); // 8 bytes: 66 0F 57 05 d32
        a.rm(Sse::CmpEqPd, Xmm(1), Mem::Pool(0)); // 9 bytes: 66 0F C2 0D d32 00
        let code = a.finish(&[0; 32]).to_vec();
        let d = i32::from_le_bytes(code[4..8].try_into().unwrap());
        // The pool starts at 32 (the code padded); the first instruction ends at 8.
        assert_eq!(8 + d as usize, 32 + 16);
        assert_eq!(&code[8..12], &[0x66, 0x0F, 0xC2, 0x0D]);
        let d = i32::from_le_bytes(code[12..16].try_into().unwrap());
        // The second ends after its immediate, at 17.
        assert_eq!((17 + d) as usize, 32);
        assert_eq!(code[16], 0);
    }
}
