//! The elastic influence operator seen by the contact solvers: `w = K p`, the
//! normal surface displacement of the body for a cell-wise constant pressure
//! (paper eq. 7's `A^(1)` part). Solvers take anything that applies `K` so that tests
//! can drive them with a small dense matrix (style: argmin's problem trait, faer's
//! `LinOp`); production uses the DC-FFT convolution, on a wrap-around grid trimmed
//! to the pressure's support when that is markedly smaller than the full `2n`
//! padding (the contact in a window with margins).

use std::sync::Arc;

use crate::convolution::{
    add_sparse_even_convolution, needed_padding, quick_padding, ConvolutionPlan, Convolver,
    KernelSpectrum, Support,
};
use crate::error::{Error, Result};
use crate::layer::{cell_mean_pressure, ContactEdge};

/// Something that applies the body's influence matrix.
///
/// Callers use [`Self::apply`] and [`Self::add_sparse`], which check their slices
/// and return an [`Error::InvalidValue`] naming the one of the wrong length (or the
/// cell outside the grid); an operator implements [`Self::apply_product`] and
/// optionally [`Self::add_sparse_update`], whose [`Product`] and [`SparseUpdate`]
/// only this crate makes, after those checks or, in the solvers' loops, from vectors
/// of the operator's length by construction (checked in debug builds).
pub trait InfluenceOperator {
    /// Number of cells.
    fn len(&self) -> usize;
    /// Whether there are no cells.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The diagonal coefficient (displacement of a cell under its own unit pressure).
    fn self_coefficient(&self) -> f64;
    /// Whether `K` is symmetric (a kernel even in x and y); conjugate gradients need
    /// it, a body that creeps in steady sliding does not give it.
    fn is_symmetric(&self) -> bool;
    /// `w = K p`, both of [`Self::len`] cells; another length is an
    /// [`Error::InvalidValue`] naming `p` or `w` and the allowed length.
    fn apply(&mut self, p: &[f64], w: &mut [f64]) -> Result<()> {
        let product = Product::checked(self.len(), p, w)?;
        self.apply_product(product);
        Ok(())
    }
    /// `w = K p` for a `p` and `w` of [`Self::len`] cells (what an operator
    /// implements; callers use [`Self::apply`]).
    fn apply_product(&mut self, product: Product<'_>);
    /// `w += K δ` for a `δ` that is non-zero on the `cells` only (`(index, value)`,
    /// indices increasing and below [`Self::len`], `w` of [`Self::len`] cells), if the
    /// operator can do that for less than a product `K p`: `Ok(true)`; `Ok(false)`
    /// (and `w` untouched) if not, and the caller applies `K` in full. Other lengths
    /// or indices are an [`Error::InvalidValue`] naming the argument.
    fn add_sparse(&mut self, cells: &[(usize, f64)], w: &mut [f64]) -> Result<bool> {
        let update = SparseUpdate::checked(self.len(), cells, w)?;
        Ok(self.add_sparse_update(update))
    }
    /// [`Self::add_sparse`] on checked arguments (what an operator implements, if
    /// it can do better than refuse: `false`, `w` untouched).
    fn add_sparse_update(&mut self, update: SparseUpdate<'_>) -> bool {
        let _ = update;
        false
    }
    /// Products `K p` computed so far (for cost accounting; 0 if not counted).
    fn products(&self) -> usize {
        0
    }
}

/// The pressure `p` and the displacement `w` of one product `w = K p`, both of the
/// operator's number of cells (checked when made).
pub struct Product<'a> {
    p: &'a [f64],
    w: &'a mut [f64],
}

impl<'a> Product<'a> {
    /// `p` and `w` if both have `cells` entries; else an error naming the first that
    /// does not.
    fn checked(cells: usize, p: &'a [f64], w: &'a mut [f64]) -> Result<Self> {
        check_length("p (pressure) length", p.len(), cells)?;
        check_length("w (displacement) length", w.len(), cells)?;
        Ok(Product { p, w })
    }

    /// For the solvers' own vectors, of the operator's length by construction.
    pub(crate) fn trusted(p: &'a [f64], w: &'a mut [f64]) -> Self {
        debug_assert_eq!(p.len(), w.len());
        Product { p, w }
    }

    /// The pressure and the displacement to write.
    pub fn into_parts(self) -> (&'a [f64], &'a mut [f64]) {
        (self.p, self.w)
    }
}

/// The cells `(index, value)` of a sparse `δ` and the displacement `w` that
/// `K δ` is added to: indices increasing and below the operator's number of cells,
/// `w` of that length (checked when made).
pub struct SparseUpdate<'a> {
    cells: &'a [(usize, f64)],
    w: &'a mut [f64],
}

impl<'a> SparseUpdate<'a> {
    /// `cells` and `w` if they fit an operator of `n` cells; else an error naming
    /// the argument.
    fn checked(n: usize, cells: &'a [(usize, f64)], w: &'a mut [f64]) -> Result<Self> {
        check_length("w (displacement) length", w.len(), n)?;
        let mut last = None;
        for &(k, _) in cells {
            if k >= n || last.is_some_and(|l| k <= l) {
                let allowed = format!(
                    "increasing indices below the operator's {n} cells{}",
                    last.map_or(String::new(), |l| format!(" (the one before is {l})"))
                );
                return Err(Error::invalid("cells index", k, &allowed));
            }
            last = Some(k);
        }
        Ok(SparseUpdate { cells, w })
    }

    /// For the solvers' own vectors (see [`Product::trusted`]).
    pub(crate) fn trusted(cells: &'a [(usize, f64)], w: &'a mut [f64]) -> Self {
        debug_assert!(cells.iter().all(|&(k, _)| k < w.len()));
        SparseUpdate { cells, w }
    }

    /// The cells and the displacement to add to.
    pub fn into_parts(self) -> (&'a [(usize, f64)], &'a mut [f64]) {
        (self.cells, self.w)
    }
}

fn check_length(name: &str, len: usize, cells: usize) -> Result<()> {
    if len == cells {
        Ok(())
    } else {
        let allowed = format!("the operator's {cells} cells");
        Err(Error::invalid(name, len, &allowed))
    }
}

/// The solvers' entries: [`InfluenceOperator::apply`] and
/// [`InfluenceOperator::add_sparse`] without their checks, for vectors the solvers
/// size from the operator themselves (a check per product would cost nothing
/// measurable, but an error there could only be a bug of this crate).
pub(crate) trait Unchecked: InfluenceOperator {
    /// `w = K p`.
    fn apply_unchecked(&mut self, p: &[f64], w: &mut [f64]) {
        self.apply_product(Product::trusted(p, w));
    }
    /// `w += K δ` if cheaper than a product (see [`InfluenceOperator::add_sparse`]).
    fn add_sparse_unchecked(&mut self, cells: &[(usize, f64)], w: &mut [f64]) -> bool {
        self.add_sparse_update(SparseUpdate::trusted(cells, w))
    }
}

impl<T: InfluenceOperator + ?Sized> Unchecked for T {}

/// `K` applied by DC-FFT with a cached kernel spectrum.
pub struct ConvolutionOperator {
    convolver: Convolver,
    kernel: Arc<KernelSpectrum>,
    /// The DC-FFT on a padding trimmed to the supports seen so far, and the kernel's
    /// spectrum there (built by this operator from the kernel's quadrant).
    trimmed: Option<(Convolver, KernelSpectrum)>,
    /// Trimmed paddings planned so far (at most [`MAX_TRIMMED_PLANS`]).
    trimmed_plans: usize,
    /// The kernel's spectrum on the full padding, built by the first product that
    /// needs it when the kernel came as its quadrant only.
    full: Option<KernelSpectrum>,
    products: usize,
}

/// Grids with fewer cells always use the full padding: planning a trimmed one and
/// its kernel spectrum costs more than it saves there.
const TRIM_MIN_CELLS: usize = 64 * 64;
/// A trimmed padding is planned only if it has at most this share of the full
/// padding's cells.
const TRIM_MAX_SHARE: f64 = 0.8;
/// Cells added around a support before planning for it, as a share of the grid, so
/// that a contact that grows a little keeps its padding.
const TRIM_MARGIN_SHARE: usize = 32;
/// Direct-summation multiply-adds ([`add_sparse_even_convolution`]) worth one
/// `padded cells x log2(padded cells)` unit of a DC-FFT product. Measured on one
/// core at 256² to 1024²: 0.21-0.25 ns a multiply-add, 0.22-0.31 ns a unit; and a
/// product the solver does instead costs it another pass or two over the cells.
const DIRECT_SUMS_PER_FFT_UNIT: f64 = 1.25;
/// Trimmed paddings one operator plans at most (a contact that keeps outgrowing
/// its padding falls back to the full one).
const MAX_TRIMMED_PLANS: usize = 3;

impl ConvolutionOperator {
    /// Pairs a scratch with a kernel spectrum built for the same grid; a kernel of
    /// another grid is an error.
    pub fn new(convolver: Convolver, kernel: Arc<KernelSpectrum>) -> Result<Self> {
        let plan = convolver.plan();
        if kernel.grid() != [plan.nx(), plan.ny()] {
            let [kx, ky] = kernel.grid();
            return Err(Error::invalid(
                "influence kernel",
                format!("a kernel of a {kx} x {ky} grid"),
                &format!("a kernel of the plan's {} x {} grid", plan.nx(), plan.ny()),
            ));
        }
        Ok(ConvolutionOperator {
            convolver,
            kernel,
            trimmed: None,
            trimmed_plans: 0,
            full: None,
            products: 0,
        })
    }

    /// The trimmed DC-FFT for a field with `support`, planned now if none held
    /// fits and one is worth planning.
    fn trimmed_for(&mut self, support: &Support) -> Option<&mut (Convolver, KernelSpectrum)> {
        let fits = |t: &Option<(Convolver, KernelSpectrum)>| {
            t.as_ref().is_some_and(|(c, _)| c.plan().holds(support))
        };
        if !fits(&self.trimmed) && self.trimmed_plans < MAX_TRIMMED_PLANS {
            let full = self.convolver.plan();
            let (nx, ny) = (full.nx(), full.ny());
            let margin = (nx.max(ny) / TRIM_MARGIN_SHARE).max(2);
            let wide = support.widened(margin, nx, ny);
            let px = quick_padding(needed_padding(nx, wide.columns), nx);
            let py = quick_padding(needed_padding(ny, wide.rows), ny);
            // A support too wide to gain from trimming keeps the trimmed padding
            // held for the others.
            if (px * py) as f64 <= TRIM_MAX_SHARE * (4 * nx * ny) as f64 {
                let plan = ConvolutionPlan::padded(nx, ny, [px, py], full.parallelism());
                let spectrum = plan.respectrum(&self.kernel);
                self.trimmed = Some((plan.convolver(), spectrum));
                self.trimmed_plans += 1;
            }
        }
        if fits(&self.trimmed) {
            self.trimmed.as_mut()
        } else {
            None
        }
    }
}

impl InfluenceOperator for ConvolutionOperator {
    fn is_symmetric(&self) -> bool {
        self.kernel.is_even()
    }
    fn len(&self) -> usize {
        self.convolver.plan().nx() * self.convolver.plan().ny()
    }
    fn self_coefficient(&self) -> f64 {
        self.kernel.self_coefficient()
    }
    fn apply_product(&mut self, product: Product<'_>) {
        let (p, w) = product.into_parts();
        self.products += 1;
        let (nx, ny) = (self.convolver.plan().nx(), self.convolver.plan().ny());
        if nx * ny >= TRIM_MIN_CELLS && self.kernel.is_even() {
            if let Some(support) = Support::of(p, nx, ny) {
                if let Some((convolver, spectrum)) = self.trimmed_for(&support) {
                    convolver.convolve(spectrum, p, w);
                    return;
                }
            }
        }
        if self.kernel.has_values() {
            self.convolver.convolve(&self.kernel, p, w);
        } else {
            let plan = self.convolver.plan();
            let full = self
                .full
                .get_or_insert_with(|| plan.respectrum(&self.kernel));
            self.convolver.convolve(full, p, w);
        }
    }
    fn add_sparse_update(&mut self, update: SparseUpdate<'_>) -> bool {
        let (cells, w) = update.into_parts();
        let Some(quadrant) = self.kernel.even_quadrant() else {
            return false;
        };
        let plan = self.convolver.plan();
        let (nx, ny) = (plan.nx(), plan.ny());
        // A product's work is that of its padding's FFTs (the trimmed padding when
        // one is held); direct summation's is a multiply-add per cell and data cell.
        let [px, py] = self
            .trimmed
            .as_ref()
            .map_or(plan.padding(), |(c, _)| c.plan().padding());
        let padded = (px * py) as f64;
        if (cells.len() * nx * ny) as f64 > DIRECT_SUMS_PER_FFT_UNIT * padded * padded.log2() {
            return false;
        }
        add_sparse_even_convolution(nx, ny, quadrant, cells, w, plan.parallelism());
        true
    }
    fn products(&self) -> usize {
        self.products
    }
}

/// A dense row-major matrix, for tests and the reference solver.
#[derive(Debug, Clone)]
pub struct DenseOperator {
    n: usize,
    values: Vec<f64>,
    symmetric: bool,
}

impl DenseOperator {
    /// Assembles `K_ij = kernel(i, j)` for `n` cells.
    pub fn from_fn(n: usize, kernel: impl Fn(usize, usize) -> f64) -> Self {
        let mut values = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                values[i * n + j] = kernel(i, j);
            }
        }
        let symmetric = (0..n).all(|i| (0..i).all(|j| values[i * n + j] == values[j * n + i]));
        DenseOperator {
            n,
            values,
            symmetric,
        }
    }

    /// Entry `(i, j)`.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.values[i * self.n + j]
    }
}

impl InfluenceOperator for DenseOperator {
    fn is_symmetric(&self) -> bool {
        self.symmetric
    }
    fn len(&self) -> usize {
        self.n
    }
    fn self_coefficient(&self) -> f64 {
        self.values.first().copied().unwrap_or(0.0)
    }
    fn apply_product(&mut self, product: Product<'_>) {
        let (p, w) = product.into_parts();
        for (i, wi) in w.iter_mut().enumerate() {
            let row = &self.values[i * self.n..(i + 1) * self.n];
            *wi = row.iter().zip(p).map(|(a, b)| a * b).sum();
        }
    }
    fn add_sparse_update(&mut self, update: SparseUpdate<'_>) -> bool {
        let (cells, w) = update.into_parts();
        for (i, wi) in w.iter_mut().enumerate() {
            let row = &self.values[i * self.n..(i + 1) * self.n];
            *wi += cells.iter().map(|&(k, v)| row[k] * v).sum::<f64>();
        }
        true
    }
}

/// `K W`: an influence operator applied to each cell's mean pressure
/// ([`crate::layer::cell_mean_pressure`]) instead of its centre value; `W` differs
/// from the identity only at the contacts' entry cells a layer places.
pub(crate) struct OnCellMeans<'a> {
    inner: &'a mut dyn InfluenceOperator,
    entries: &'a [ContactEdge],
    means: Vec<f64>,
}

impl<'a> OnCellMeans<'a> {
    /// `inner` applied to the mean pressures of `entries`.
    pub(crate) fn new(inner: &'a mut dyn InfluenceOperator, entries: &'a [ContactEdge]) -> Self {
        let n = inner.len();
        OnCellMeans {
            inner,
            entries,
            means: vec![0.0; n],
        }
    }
}

impl InfluenceOperator for OnCellMeans<'_> {
    fn is_symmetric(&self) -> bool {
        self.entries.is_empty() && self.inner.is_symmetric()
    }
    fn len(&self) -> usize {
        self.inner.len()
    }
    fn self_coefficient(&self) -> f64 {
        self.inner.self_coefficient()
    }
    fn apply_product(&mut self, product: Product<'_>) {
        let (p, w) = product.into_parts();
        if self.entries.is_empty() {
            return self.inner.apply_unchecked(p, w);
        }
        cell_mean_pressure(self.entries, p, &mut self.means);
        self.inner.apply_unchecked(&self.means, w);
    }
    fn products(&self) -> usize {
        self.inner.products()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::convolution::Parallelism;

    #[test]
    fn the_operator_trims_for_a_small_support_and_gives_the_full_padding_result() {
        let (nx, ny) = (96, 80);
        let kernel = |di: i64, dj: i64| 1.0 / (0.5 + ((di * di + dj * dj) as f64).sqrt());
        let quadrant: Vec<f64> = (0..nx * ny)
            .map(|k| kernel((k % nx) as i64, (k / nx) as i64))
            .collect();
        let plan = ConvolutionPlan::new(nx, ny, Parallelism::Sequential).unwrap();
        let spectrum = Arc::new(plan.even_kernel_spectrum(&quadrant));
        // The operator gets the kernel as its quadrant only, as from a KernelCache.
        let lazy = Arc::new(plan.even_kernel(quadrant.clone()).unwrap());
        let mut op = ConvolutionOperator::new(plan.convolver(), lazy).unwrap();
        let mut reference = plan.convolver();
        // A disc of data in the middle, then a wider one, the whole grid, and the
        // first disc again.
        let (first, second) = ([144, 128], [160, 144]);
        for (radius, expected) in [
            (20.0, first),
            (30.0, second),
            (200.0, second),
            (20.0, second),
        ] {
            let field: Vec<f64> = (0..nx * ny)
                .map(|k| {
                    let (x, y) = ((k % nx) as f64 - 47.5, (k / nx) as f64 - 39.5);
                    let r2 = (x * x + y * y) / (radius * radius);
                    (1.0 - r2).max(0.0).sqrt()
                })
                .collect();
            let (mut fast, mut full) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
            op.apply(&field, &mut fast).unwrap();
            reference.apply(&spectrum, &field, &mut full).unwrap();
            let scale = full.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (a, b) in fast.iter().zip(&full) {
                assert!((a - b).abs() < 1e-13 * scale, "radius {radius}");
            }
            let trimmed = op.trimmed.as_ref().map(|(c, _)| c.plan().padding());
            // The first disc: 96 cells, data from 27 to 68 widened by 3: 2 x 71 =
            // 142 -> 9 x 16 (and 124 -> 128 on the 80 rows). The wider one: data
            // from 18 to 77 widened by 3: 2 x 80 = 160 = 5 x 32 (144 = 9 x 16). It
            // holds the whole grid's data only on the full padding, so keeps the
            // second, which serves the first disc again.
            assert_eq!(trimmed, Some(expected), "radius {radius}");
        }
        // The wide supports were not worth a padding of their own and did not drop
        // the one planned for the discs.
        assert_eq!(op.trimmed_plans, 2);
        assert!(
            op.full.is_some(),
            "the wide supports built the full spectrum"
        );
        assert_eq!(op.products(), 4);
    }

    #[test]
    fn a_kernel_of_another_grid_is_an_error() {
        let kernel_plan = ConvolutionPlan::new(12, 10, Parallelism::Sequential).unwrap();
        let kernel = Arc::new(kernel_plan.even_kernel(vec![1.0; 120]).unwrap());
        let plan = ConvolutionPlan::new(10, 12, Parallelism::Sequential).unwrap();
        let e = ConvolutionOperator::new(plan.convolver(), kernel)
            .err()
            .unwrap();
        let message = e.to_string();
        assert!(message.contains("influence kernel"), "{message}");
        assert!(
            message.contains("12 x 10") && message.contains("10 x 12"),
            "{message}"
        );
    }

    #[test]
    fn slices_of_another_length_are_errors_naming_the_argument() {
        let plan = ConvolutionPlan::new(6, 5, Parallelism::Sequential).unwrap();
        let kernel = Arc::new(plan.even_kernel(vec![1.0; 30]).unwrap());
        let mut convolution = ConvolutionOperator::new(plan.convolver(), kernel).unwrap();
        let mut dense = DenseOperator::from_fn(30, |i, j| 1.0 / (1.0 + i.abs_diff(j) as f64));
        let operators: [&mut dyn InfluenceOperator; 2] = [&mut convolution, &mut dense];
        for op in operators {
            let (p, mut w) = (vec![1.0; 30], vec![7.0; 30]);
            for (p_len, w_len, named) in [
                (29, 30, "p (pressure) length"),
                (31, 30, "p (pressure) length"),
                (30, 0, "w (displacement) length"),
                (30, 64, "w (displacement) length"),
            ] {
                let (p_other, mut w_other) = (vec![1.0; p_len], vec![7.0; w_len]);
                let e = op.apply(&p_other, &mut w_other).unwrap_err();
                let message = e.to_string();
                assert!(message.contains(named), "{message}");
                assert!(message.contains("the operator's 30 cells"), "{message}");
                assert!(w_other.iter().all(|&v| v == 7.0), "w left as it was");
            }
            let e = op.add_sparse(&[(3, 1.0)], &mut w[..29]).unwrap_err();
            assert!(e.to_string().contains("w (displacement) length"), "{e}");
            for cells in [
                &[(30, 1.0)][..],
                &[(4, 1.0), (4, 2.0)],
                &[(5, 1.0), (2, 1.0)],
            ] {
                let e = op.add_sparse(cells, &mut w).unwrap_err();
                assert!(e.to_string().contains("cells index"), "{e}");
            }
            assert!(w.iter().all(|&v| v == 7.0), "w left as it was");
            // The right lengths: the product.
            op.apply(&p, &mut w).unwrap();
            assert!(w.iter().all(|v| v.is_finite() && *v != 7.0));
        }
        // An empty dense operator has no diagonal to give, and does not panic.
        assert_eq!(
            DenseOperator::from_fn(0, |_, _| 1.0).self_coefficient(),
            0.0
        );
    }

    #[test]
    fn direct_sums_are_taken_for_a_few_cells_and_refused_for_many() {
        let (nx, ny) = (40, 30);
        let kernel = |di: i64, dj: i64| 1.0 / (0.5 + ((di * di + 2 * dj * dj) as f64).sqrt());
        let quadrant: Vec<f64> = (0..nx * ny)
            .map(|k| kernel((k % nx) as i64, (k / nx) as i64))
            .collect();
        let plan = ConvolutionPlan::new(nx, ny, Parallelism::Sequential).unwrap();
        let kernel = Arc::new(plan.even_kernel(quadrant).unwrap());
        let mut op = ConvolutionOperator::new(plan.convolver(), kernel).unwrap();
        let cells = [(5, 0.5), (7 * nx + 39, -1.5), (29 * nx + 20, 2.0)];
        let mut field = vec![0.0; nx * ny];
        for &(k, v) in &cells {
            field[k] = v;
        }
        let mut product = vec![0.0; nx * ny];
        op.apply(&field, &mut product).unwrap();
        let start: Vec<f64> = (0..nx * ny).map(|k| (k % 3) as f64).collect();
        let mut w = start.clone();
        assert!(op.add_sparse(&cells, &mut w).unwrap());
        for k in 0..nx * ny {
            assert!((w[k] - start[k] - product[k]).abs() < 1e-13, "cell {k}");
        }
        // Every cell: a product is cheaper (1200 x 1200 multiply-adds against
        // 1.25 x 4800 x log2 4800), and `w` is left as it was.
        let all: Vec<(usize, f64)> = (0..nx * ny).map(|k| (k, 1.0)).collect();
        let mut w = start.clone();
        assert!(!op.add_sparse(&all, &mut w).unwrap());
        assert_eq!(w, start);
    }
}
