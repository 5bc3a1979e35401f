//! Small quadrature and interpolation tools for the coated-body kernel:
//! Gauss–Legendre rules (nodes from Newton's method on the Legendre recurrence;
//! Davis & Rabinowitz, Methods of Numerical Integration, §2.7) and piecewise
//! Chebyshev interpolation of a smooth function on an interval (Trefethen,
//! Approximation Theory and Approximation Practice, ch. 3: interpolation in the
//! Chebyshev points of the first kind, evaluated by Clenshaw's recurrence).

/// A Gauss–Legendre rule on [-1, 1].
#[derive(Debug, Clone)]
pub struct GaussLegendre {
    /// Nodes in increasing order.
    pub nodes: Vec<f64>,
    /// Weights, summing to 2.
    pub weights: Vec<f64>,
}

impl GaussLegendre {
    /// The `n`-point rule (exact for polynomials of degree 2n - 1).
    pub fn new(n: usize) -> Self {
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        for i in 0..n.div_ceil(2) {
            // Tricomi's initial guess, then Newton on P_n.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut derivative = 1.0;
            for _ in 0..100 {
                let (p, dp) = legendre_with_derivative(n, x);
                derivative = dp;
                let step = p / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let (_, dp) = legendre_with_derivative(n, x);
            if dp.is_finite() {
                derivative = dp;
            }
            let w = 2.0 / ((1.0 - x * x) * derivative * derivative);
            nodes[i] = -x;
            nodes[n - 1 - i] = x;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        if n % 2 == 1 {
            nodes[n / 2] = 0.0;
        }
        GaussLegendre { nodes, weights }
    }

    /// `int_lo^hi g(x) dx` by this rule.
    pub fn integrate(&self, lo: f64, hi: f64, mut g: impl FnMut(f64) -> f64) -> f64 {
        let half = 0.5 * (hi - lo);
        let mid = 0.5 * (hi + lo);
        let mut sum = 0.0;
        for (x, w) in self.nodes.iter().zip(&self.weights) {
            sum += w * g(mid + half * x);
        }
        sum * half
    }
}

/// `(P_n(x), P_n'(x))` by the three-term recurrence.
fn legendre_with_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

/// A smooth function on `[lo, hi]` as equal panels, each a Chebyshev series.
#[derive(Debug, Clone)]
pub struct ChebyshevPanels {
    lo: f64,
    width: f64,
    degree: usize,
    /// Coefficients, `degree` per panel.
    coefficients: Vec<f64>,
}

impl ChebyshevPanels {
    /// The Chebyshev points (first kind) of `panels` equal panels on `[lo, hi]`,
    /// `degree` per panel, panel after panel: sample the function there and pass
    /// the values to [`ChebyshevPanels::from_values`].
    pub fn points(lo: f64, hi: f64, panels: usize, degree: usize) -> Vec<f64> {
        let width = (hi - lo) / panels as f64;
        let mut x = Vec::with_capacity(panels * degree);
        for p in 0..panels {
            let mid = lo + (p as f64 + 0.5) * width;
            for k in 0..degree {
                let c = (std::f64::consts::PI * (k as f64 + 0.5) / degree as f64).cos();
                x.push(mid + 0.5 * width * c);
            }
        }
        x
    }

    /// The interpolant of the values taken at [`ChebyshevPanels::points`].
    pub fn from_values(lo: f64, hi: f64, panels: usize, degree: usize, values: &[f64]) -> Self {
        Self::from_values_with(lo, hi, panels, &Self::dct_cosines(degree), values)
    }

    /// The cosines of the DCT that [`ChebyshevPanels::from_values`] takes at `degree`
    /// points, `[j * degree + k]`: the same for every panel and every function, so a
    /// caller building many interpolants computes them once.
    pub fn dct_cosines(degree: usize) -> Vec<f64> {
        (0..degree * degree)
            .map(|jk| {
                let (j, k) = (jk / degree, jk % degree);
                (std::f64::consts::PI * j as f64 * (k as f64 + 0.5) / degree as f64).cos()
            })
            .collect()
    }

    /// [`ChebyshevPanels::from_values`] with the DCT's cosines given
    /// ([`ChebyshevPanels::dct_cosines`]; their count sets the degree).
    pub fn from_values_with(
        lo: f64,
        hi: f64,
        panels: usize,
        cosines: &[f64],
        values: &[f64],
    ) -> Self {
        let degree = (cosines.len() as f64).sqrt().round() as usize;
        assert_eq!(degree * degree, cosines.len(), "a square table of cosines");
        let width = (hi - lo) / panels as f64;
        let mut coefficients = vec![0.0; panels * degree];
        for p in 0..panels {
            let v = &values[p * degree..(p + 1) * degree];
            for j in 0..degree {
                let row = &cosines[j * degree..(j + 1) * degree];
                let s: f64 = v.iter().zip(row).map(|(vk, c)| vk * c).sum();
                let scale = if j == 0 { 1.0 } else { 2.0 } / degree as f64;
                coefficients[p * degree + j] = s * scale;
            }
        }
        ChebyshevPanels {
            lo,
            width,
            degree,
            coefficients,
        }
    }

    /// The panel of `x` and the position `u` in [-1, 1] within it.
    fn locate(&self, x: f64) -> (usize, f64) {
        let panels = self.coefficients.len() / self.degree;
        let p = (((x - self.lo) / self.width).floor().max(0.0) as usize).min(panels - 1);
        let mid = self.lo + (p as f64 + 0.5) * self.width;
        (p, 2.0 * (x - mid) / self.width)
    }

    /// The interpolant at `x` (panels extrapolate slightly beyond `[lo, hi]`).
    pub fn eval(&self, x: f64) -> f64 {
        let (p, u) = self.locate(x);
        let c = &self.coefficients[p * self.degree..(p + 1) * self.degree];
        // Clenshaw.
        let (mut b1, mut b2) = (0.0, 0.0);
        for &cj in c.iter().skip(1).rev() {
            let b0 = 2.0 * u * b1 - b2 + cj;
            b2 = b1;
            b1 = b0;
        }
        u * b1 - b2 + c[0]
    }
}

/// `N` functions on the same panels (same `lo`, `hi`, panel count and degree),
/// evaluated together: one panel lookup and `N` Clenshaw recurrences run side by
/// side, so that their dependency chains overlap. Each value is computed with exactly
/// the operations of [`ChebyshevPanels::eval`], so the results are bitwise equal.
#[derive(Debug, Clone)]
pub struct InterleavedPanels<const N: usize> {
    /// The panels' layout (the first function's).
    layout: ChebyshevPanels,
    /// Coefficient `j` of panel `p` for the `N` functions at `p * degree + j`.
    coefficients: Vec<[f64; N]>,
}

impl<const N: usize> InterleavedPanels<N> {
    /// Interleaves `N` interpolants built on the same panels.
    ///
    /// # Panics
    /// If the interpolants do not share their panels (a programming error).
    pub fn new(functions: [ChebyshevPanels; N]) -> Self {
        let first = &functions[0];
        for f in &functions {
            assert!(
                f.lo == first.lo
                    && f.width == first.width
                    && f.degree == first.degree
                    && f.coefficients.len() == first.coefficients.len(),
                "interleaved Chebyshev panels must share their layout"
            );
        }
        let coefficients = (0..first.coefficients.len())
            .map(|k| std::array::from_fn(|q| functions[q].coefficients[k]))
            .collect();
        InterleavedPanels {
            layout: first.clone(),
            coefficients,
        }
    }

    /// The `N` interpolants at `x`.
    #[inline]
    pub fn eval(&self, x: f64) -> [f64; N] {
        let (p, u) = self.layout.locate(x);
        let degree = self.layout.degree;
        let c = &self.coefficients[p * degree..(p + 1) * degree];
        let (mut b1, mut b2) = ([0.0; N], [0.0; N]);
        for cj in c.iter().skip(1).rev() {
            for q in 0..N {
                let b0 = 2.0 * u * b1[q] - b2[q] + cj[q];
                b2[q] = b1[q];
                b1[q] = b0;
            }
        }
        std::array::from_fn(|q| u * b1[q] - b2[q] + c[0][q])
    }

    /// [`Self::eval`] at `BATCH` points at once, each with exactly its operations (the
    /// results are bitwise equal): the points' recurrences run side by side, so that
    /// their dependency chains overlap (one point's Clenshaw step waits on its
    /// previous step; `BATCH` points fill the waits).
    #[inline]
    pub fn eval_batch<const BATCH: usize>(&self, xs: [f64; BATCH]) -> [[f64; N]; BATCH] {
        let degree = self.layout.degree;
        let located: [(usize, f64); BATCH] = xs.map(|x| self.layout.locate(x));
        let mut b1 = [[0.0; N]; BATCH];
        let mut b2 = [[0.0; N]; BATCH];
        for j in (1..degree).rev() {
            for (i, &(p, u)) in located.iter().enumerate() {
                let cj = &self.coefficients[p * degree + j];
                for q in 0..N {
                    let b0 = 2.0 * u * b1[i][q] - b2[i][q] + cj[q];
                    b2[i][q] = b1[i][q];
                    b1[i][q] = b0;
                }
            }
        }
        std::array::from_fn(|i| {
            let (p, u) = located[i];
            let c0 = &self.coefficients[p * degree];
            std::array::from_fn(|q| u * b1[i][q] - b2[i][q] + c0[q])
        })
    }
}

/// Any number of functions on the same Chebyshev panels, evaluated together: the
/// Chebyshev polynomials at a point are computed once (three-term recurrence) and
/// each function's value is their dot product with its coefficients, so the cost per
/// extra function is one short dot product.
#[derive(Debug, Clone)]
pub struct SharedPanels {
    /// The panels' layout (the first function's).
    layout: ChebyshevPanels,
    /// Per panel, the coefficients of all functions: `((p * n_functions) + f) * degree + j`.
    coefficients: Vec<f64>,
    functions: usize,
}

impl SharedPanels {
    /// Interpolants of the columns of `values`: `values[f]` sampled at
    /// [`ChebyshevPanels::points`]`(lo, hi, panels, degree)`.
    pub fn from_values(
        lo: f64,
        hi: f64,
        panels: usize,
        degree: usize,
        values: &[Vec<f64>],
    ) -> Self {
        let per: Vec<ChebyshevPanels> = values
            .iter()
            .map(|v| ChebyshevPanels::from_values(lo, hi, panels, degree, v))
            .collect();
        let layout =
            ChebyshevPanels::from_values(lo, hi, panels, degree, &vec![0.0; panels * degree]);
        let mut coefficients = Vec::with_capacity(panels * degree * per.len());
        for p in 0..panels {
            for f in &per {
                coefficients.extend_from_slice(&f.coefficients[p * degree..(p + 1) * degree]);
            }
        }
        SharedPanels {
            layout,
            coefficients,
            functions: per.len(),
        }
    }

    /// Every function's interpolant at `x`, written to `out` (one per function).
    pub fn eval_into(&self, x: f64, out: &mut [f64]) {
        let (p, u) = self.layout.locate(x);
        let degree = self.layout.degree;
        let mut t = [0.0f64; 64];
        let t = &mut t[..degree.min(64)];
        t[0] = 1.0;
        if degree > 1 {
            t[1] = u;
        }
        for j in 2..t.len() {
            t[j] = 2.0 * u * t[j - 1] - t[j - 2];
        }
        let block =
            &self.coefficients[p * self.functions * degree..(p + 1) * self.functions * degree];
        for (o, c) in out.iter_mut().zip(block.chunks_exact(degree)) {
            *o = c.iter().zip(t.iter()).map(|(a, b)| a * b).sum();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_and_exp_exactly() {
        for n in [1, 2, 5, 10, 16] {
            let rule = GaussLegendre::new(n);
            assert!((rule.weights.iter().sum::<f64>() - 2.0).abs() < 1e-14);
            // x^(2n-2) over [-1, 1] = 2 / (2n - 1).
            let m = 2 * n as i32 - 2;
            let s = rule.integrate(-1.0, 1.0, |x| x.powi(m));
            assert!((s - 2.0 / (m + 1) as f64).abs() < 1e-14, "n = {n}: {s}");
        }
        let rule = GaussLegendre::new(12);
        let s = rule.integrate(0.0, 1.0, f64::exp);
        assert!((s - (1f64.exp() - 1.0)).abs() < 1e-15);
    }

    #[test]
    fn chebyshev_panels_interpolate_a_smooth_function() {
        let (lo, hi) = (-2.0, 3.0);
        let x = ChebyshevPanels::points(lo, hi, 5, 16);
        let values: Vec<f64> = x.iter().map(|&x| (x.sin() + 0.3 * x).exp()).collect();
        let c = ChebyshevPanels::from_values(lo, hi, 5, 16, &values);
        for k in 0..=1000 {
            let x = lo + (hi - lo) * k as f64 / 1000.0;
            let exact = (x.sin() + 0.3 * x).exp();
            assert!((c.eval(x) - exact).abs() < 1e-13 * exact, "{x}");
        }
    }

    #[test]
    fn interleaved_panels_equal_the_single_ones_bitwise() {
        let f = |x: f64, q: usize| (x * (q as f64 + 0.5)).sin() * (-0.1 * x).exp() + q as f64;
        let points = ChebyshevPanels::points(0.0, 7.0, 5, 12);
        let singles: [ChebyshevPanels; 3] = std::array::from_fn(|q| {
            let v: Vec<f64> = points.iter().map(|&x| f(x, q)).collect();
            ChebyshevPanels::from_values(0.0, 7.0, 5, 12, &v)
        });
        let together = InterleavedPanels::new(singles.clone());
        for k in 0..=400 {
            let x = -0.1 + 7.2 * k as f64 / 400.0;
            let got = together.eval(x);
            // In a batch with points of other panels.
            let batch = together.eval_batch([6.9 - x, x, 0.5 * x, 3.3]);
            assert_eq!(batch[1].map(f64::to_bits), got.map(f64::to_bits), "x = {x}");
            assert_eq!(
                batch[0].map(f64::to_bits),
                together.eval(6.9 - x).map(f64::to_bits)
            );
            for q in 0..3 {
                assert_eq!(
                    got[q].to_bits(),
                    singles[q].eval(x).to_bits(),
                    "x = {x}, q = {q}"
                );
                if (0.0..=7.0).contains(&x) {
                    assert!(
                        (got[q] - f(x, q)).abs() < 1e-9,
                        "interpolation error at {x}"
                    );
                }
            }
        }
    }
}
