//! Modal intervals and Kaucher arithmetic on the worked examples of the thesis (§3.5): the
//! sum `[1, 3] + [3, 2]` with its two logical readings, and the three rational extensions of
//! `f(x, y) = xy / (x + y)` at `X = [2, 3]`, `Y = [4, 3]`, each evaluated with outer and
//! inner rounding.
//!
//! Run with `cargo run --release -p examples --bin modal_example`.

use interval_core::IntervalError;
use interval_core::modal::{Inner, Modal, Outer, Rounding};

/// The rational extensions of `f(x, y) = xy / (x + y)` chosen by theorems 5, 3 and 6, in
/// the rounding `R`.
fn extensions<T: interval_core::Float, R: Rounding>() -> Result<[Modal<T, R>; 3], IntervalError> {
    let c = |v: f64| T::from_f64_rn(v);
    let x = Modal::<T, R>::proper(c(2.0), c(3.0))?;
    let y = Modal::<T, R>::improper(c(4.0), c(3.0))?;
    let four = Modal::<T, R>::point(c(4.0))?;
    Ok([
        // Theorem 5: the improper multi-incident y becomes the point [4, 4].
        x * four / (x + four),
        // Theorem 3: also the incidence x2, where f decreases, is dualized.
        x * four / (x.dual() + four),
        // Theorem 6: f is totally monotonic and tree-optimal, so fR(XD) = f* = f**.
        x * y / (x.dual() + y.dual()),
    ])
}

fn main() -> Result<(), IntervalError> {
    println!("Modal intervals and Kaucher arithmetic (thesis section 3.5)");
    println!();

    let x: Modal = Modal::proper(1.0, 3.0)?;
    let y: Modal = Modal::improper(3.0, 2.0)?;
    let z = x + y;
    let z_inner = x.with_rounding::<Inner>() + y.with_rounding::<Inner>();
    println!("{x} + {y} = {z}   (inner rounding: {z_inner}; the sum is exact)");
    println!("  *-semantics,  f*(X) ⊆ Z:  ∀x∈[1,3]' ∃z∈[4,5]' ∃y∈[2,3]': x + y = z");
    println!("  **-semantics, f**(X) ⊇ Z: ∀y∈[2,3]' ∀z∈[4,5]' ∃x∈[1,3]': x + y = z");
    println!();

    println!("f(x, y) = xy / (x + y),  X = [2, 3],  Y = [4, 3] (improper)");
    println!("Incidences f(x1, y1, x2, y2) = x1·y1 / (x2 + y2) on Prop(X):");
    println!("  ∂f/∂x1 > 0, ∂f/∂y1 > 0, ∂f/∂x2 < 0, ∂f/∂y2 < 0 (f itself increases in x and y)");
    let outer = extensions::<f64, Outer>()?;
    let inner = extensions::<f64, Inner>()?;
    let rows = [
        (
            "Theorem 5, Xt*  = ([2,3], [4,4], [2,3], [4,4]): X·[4,4] / (X + [4,4])",
            "[8/7, 2]",
        ),
        (
            "Theorem 3, XDt* = ([2,3], [4,4], [3,2], [4,4]): X·[4,4] / (Dual(X) + [4,4])",
            "[4/3, 12/7]",
        ),
        (
            "Theorem 6, XD   = ([2,3], [4,3], [3,2], [3,4]): X·Y / (Dual(X) + Dual(Y))",
            "[4/3, 3/2]",
        ),
    ];
    for ((title, exact), (out, inn)) in rows.iter().zip(outer.iter().zip(inner.iter())) {
        println!("{title}");
        println!(
            "  exact {exact:<12} outer {:<40} inner {inn}",
            out.to_string()
        );
    }
    let [t5, t3, t6] = outer;
    println!(
        "Out(fR(XD)) ⊆ Out(fR(XDt*)) ⊆ Out(fR(Xt*)): {}, {}",
        t6.subset(t3),
        t3.subset(t5)
    );
    println!(
        "Inn(fR(XD)) ⊆ Out(fR(XD)), with f*(X) = f**(X) between them: {}",
        inner[2].with_rounding::<Outer>().subset(t6)
    );
    let [_, _, t6_f32] = extensions::<f32, Outer>()?;
    let [_, _, t6_f32_inner] = extensions::<f32, Inner>()?;
    println!("Theorem 6 in f32: outer {t6_f32}, inner {t6_f32_inner}");
    println!();

    println!("Readings of f*(X) = [4/3, 3/2] (x proper, y improper):");
    println!("  *-semantics with Z = Out(fR(XD)) = {t6}:");
    println!("    ∀x∈[2,3]' ∃z∈Z' ∃y∈[3,4]': xy/(x+y) = z");
    println!("  **-semantics with Z = Inn(fR(XD)) = {}:", inner[2]);
    println!("    ∀y∈[3,4]' ∀z∈Z' ∃x∈[2,3]': xy/(x+y) = z");
    Ok(())
}
