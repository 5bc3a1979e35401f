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
    /// `w = K p`, both of [`Self::len`] cells (the solvers' own vectors; another
    /// length is a programming error and panics, as a slice copy does).
    fn apply(&mut self, p: &[f64], w: &mut [f64]);
    /// `w += K δ` for a `δ` that is non-zero on the `cells` only (`(index, value)`,
    /// indices increasing), if the operator can do that for less than a product
    /// `K p`; `false` (and `w` untouched) if not, and the caller applies `K` in full.
    fn add_sparse(&mut self, cells: &[(usize, f64)], w: &mut [f64]) -> bool {
        let _ = (cells, w);
        false
    }
    /// Products `K p` computed so far (for cost accounting; 0 if not counted).
    fn products(&self) -> usize {
        0
    }
}

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
    fn apply(&mut self, p: &[f64], w: &mut [f64]) {
        self.products += 1;
        let (nx, ny) = (self.convolver.plan().nx(), self.convolver.plan().ny());
        if nx * ny >= TRIM_MIN_CELLS && self.kernel.is_even() {
            if let Some(support) = Support::of(p, nx, ny) {
                if let Some((convolver, spectrum)) = self.trimmed_for(&support) {
                    convolver.apply(spectrum, p, w);
                    return;
                }
            }
        }
        if self.kernel.has_values() {
            self.convolver.apply(&self.kernel, p, w);
        } else {
            let plan = self.convolver.plan();
            let full = self
                .full
                .get_or_insert_with(|| plan.respectrum(&self.kernel));
            self.convolver.apply(full, p, w);
        }
    }
    fn add_sparse(&mut self, cells: &[(usize, f64)], w: &mut [f64]) -> bool {
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
        self.values[0]
    }
    fn apply(&mut self, p: &[f64], w: &mut [f64]) {
        for (i, wi) in w.iter_mut().enumerate() {
            let row = &self.values[i * self.n..(i + 1) * self.n];
            *wi = row.iter().zip(p).map(|(a, b)| a * b).sum();
        }
    }
    fn add_sparse(&mut self, cells: &[(usize, f64)], w: &mut [f64]) -> bool {
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
    fn apply(&mut self, p: &[f64], w: &mut [f64]) {
        if self.entries.is_empty() {
            return self.inner.apply(p, w);
        }
        cell_mean_pressure(self.entries, p, &mut self.means);
        self.inner.apply(&self.means, w);
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
        let plan = ConvolutionPlan::new(nx, ny, Parallelism::Sequential);
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
            op.apply(&field, &mut fast);
            reference.apply(&spectrum, &field, &mut full);
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
        let kernel_plan = ConvolutionPlan::new(12, 10, Parallelism::Sequential);
        let kernel = Arc::new(kernel_plan.even_kernel(vec![1.0; 120]).unwrap());
        let plan = ConvolutionPlan::new(10, 12, Parallelism::Sequential);
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
    fn direct_sums_are_taken_for_a_few_cells_and_refused_for_many() {
        let (nx, ny) = (40, 30);
        let kernel = |di: i64, dj: i64| 1.0 / (0.5 + ((di * di + 2 * dj * dj) as f64).sqrt());
        let quadrant: Vec<f64> = (0..nx * ny)
            .map(|k| kernel((k % nx) as i64, (k / nx) as i64))
            .collect();
        let plan = ConvolutionPlan::new(nx, ny, Parallelism::Sequential);
        let kernel = Arc::new(plan.even_kernel(quadrant).unwrap());
        let mut op = ConvolutionOperator::new(plan.convolver(), kernel).unwrap();
        let cells = [(5, 0.5), (7 * nx + 39, -1.5), (29 * nx + 20, 2.0)];
        let mut field = vec![0.0; nx * ny];
        for &(k, v) in &cells {
            field[k] = v;
        }
        let mut product = vec![0.0; nx * ny];
        op.apply(&field, &mut product);
        let start: Vec<f64> = (0..nx * ny).map(|k| (k % 3) as f64).collect();
        let mut w = start.clone();
        assert!(op.add_sparse(&cells, &mut w));
        for k in 0..nx * ny {
            assert!((w[k] - start[k] - product[k]).abs() < 1e-13, "cell {k}");
        }
        // Every cell: a product is cheaper (1200 x 1200 multiply-adds against
        // 1.25 x 4800 x log2 4800), and `w` is left as it was.
        let all: Vec<(usize, f64)> = (0..nx * ny).map(|k| (k, 1.0)).collect();
        let mut w = start.clone();
        assert!(!op.add_sparse(&all, &mut w));
        assert_eq!(w, start);
    }
}
