//! Discrete-convolution FFT (DC-FFT; Liu, Wang & Liu, Wear 243, 2000): the linear
//! convolution `w(x_i, y_j) = sum_{k,l} K(x_i - x_k, y_j - y_l) p_{k,l}` of a field on
//! an `nx x ny` grid with a kernel given at every cell offset, computed exactly (no
//! periodic images) by zero-padding to a `2nx x 2ny` wrap-around grid.
//!
//! [`ConvolutionPlan`] holds the FFT plans and is built once per grid size;
//! [`KernelSpectrum`] is one kernel's real-to-complex spectrum on the padded grid,
//! built once per grid and material; [`Convolver`] owns the scratch of one thread of
//! work, so that applying a kernel allocates nothing. The 2-D real FFT is done as
//! row transforms (realfft) then column transforms (rustfft); rows of the padded
//! input that are all zero and output rows that are not wanted are skipped, and the
//! row and column stages run on rayon when [`Parallelism::Rayon`] is chosen.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use crate::error::{Error, Result};

/// Whether one operation may use several threads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Parallelism {
    /// One thread (use inside a parallel sweep).
    Sequential,
    /// The rayon pool (use for one big solve).
    #[default]
    Rayon,
}

/// FFT plans for the DC-FFT of one grid size, on a wrap-around grid of `px x py`
/// (`2nx x 2ny` unless trimmed to a field's support, see `needed_padding`).
pub struct ConvolutionPlan {
    nx: usize,
    ny: usize,
    px: usize,
    py: usize,
    row_forward: Arc<dyn RealToComplex<f64>>,
    row_inverse: Arc<dyn ComplexToReal<f64>>,
    column_forward: Arc<dyn Fft<f64>>,
    column_inverse: Arc<dyn Fft<f64>>,
    parallelism: Parallelism,
}

impl std::fmt::Debug for ConvolutionPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ConvolutionPlan")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("px", &self.px)
            .field("py", &self.py)
            .field("parallelism", &self.parallelism)
            .finish()
    }
}

/// A kernel's spectrum on the padded grid, already divided by the FFT
/// normalisation.
#[derive(Debug, Clone)]
pub struct KernelSpectrum {
    nx: usize,
    ny: usize,
    px: usize,
    py: usize,
    values: SpectrumValues,
    /// The kernel at zero offset (the self-influence of a cell).
    self_coefficient: f64,
    /// The constant the kernel was lowered by before its spectrum was built (a
    /// line contact's kernel is defined up to a constant, its datum: the body's
    /// displacement is this spectrum's product plus the shift times the sum of the
    /// field); 0 for a point contact's.
    datum_shift: f64,
}

/// The stored values of a kernel spectrum.
#[derive(Debug, Clone, PartialEq)]
enum SpectrumValues {
    /// Any kernel: column-major, `nx + 1` columns of `2 ny` complex values.
    General(Vec<Complex<f64>>),
    /// A kernel even in x and in y has a real spectrum that is even in the column
    /// frequency: `px/2 + 1` columns of its first `py/2 + 1` real values, a quarter
    /// of the memory (and of the memory traffic of each product). The kernel's
    /// quadrant is kept to build its spectrum on other paddings; a kernel given by
    /// its quadrant only ([`ConvolutionPlan::even_kernel`]) has no values until
    /// [`ConvolutionPlan::respectrum`] builds them.
    Even {
        values: Option<Vec<f64>>,
        quadrant: Arc<Vec<f64>>,
    },
}

impl KernelSpectrum {
    /// Cells `[nx, ny]` of the grid the kernel was built for.
    pub fn grid(&self) -> [usize; 2] {
        [self.nx, self.ny]
    }

    /// Bytes held by the spectrum.
    pub fn bytes(&self) -> usize {
        match &self.values {
            SpectrumValues::General(v) => v.len() * std::mem::size_of::<Complex<f64>>(),
            SpectrumValues::Even { values, quadrant } => {
                (values.as_ref().map_or(0, Vec::len) + quadrant.len()) * std::mem::size_of::<f64>()
            }
        }
    }

    /// Multiplies the columns from `first_column` on (`2 ny` values each) by the
    /// spectrum, in place, or writes `field` times the spectrum when given.
    fn multiply_columns(
        &self,
        first_column: usize,
        columns: &mut [Complex<f64>],
        field: Option<&[Complex<f64>]>,
    ) {
        let (py, hy) = (self.py, self.py / 2 + 1);
        match &self.values {
            SpectrumValues::General(values) => {
                let k = &values[first_column * py..][..columns.len()];
                match field {
                    Some(f) => columns
                        .iter_mut()
                        .zip(f.iter().zip(k))
                        .for_each(|(c, (f, k))| *c = f * k),
                    None => columns.iter_mut().zip(k).for_each(|(c, k)| *c *= k),
                }
            }
            SpectrumValues::Even { values, .. } => {
                let values = values.as_ref().expect("checked by check_sizes");
                for (q, col) in columns.chunks_exact_mut(py).enumerate() {
                    let k = &values[(first_column + q) * hy..][..hy];
                    if let Some(f) = field {
                        col.copy_from_slice(&f[q * py..][..py]);
                    }
                    // Rows 0..=py/2, then py/2+1..py mirrored onto py/2-1..1.
                    let (low, high) = col.split_at_mut(hy);
                    low.iter_mut().zip(k).for_each(|(c, k)| *c *= *k);
                    high.iter_mut()
                        .zip(k[1..py / 2].iter().rev())
                        .for_each(|(c, k)| *c *= *k);
                }
            }
        }
    }

    /// Whether the spectrum's values are built (a kernel given by its quadrant only
    /// has none, see [`ConvolutionPlan::even_kernel`]).
    pub fn has_values(&self) -> bool {
        !matches!(self.values, SpectrumValues::Even { values: None, .. })
    }

    /// Whether the kernel is even in x and in y (and so can be used on a trimmed
    /// padding, [`ConvolutionPlan::respectrum`]).
    pub fn is_even(&self) -> bool {
        matches!(self.values, SpectrumValues::Even { .. })
    }

    /// The kernel on one quadrant of offsets (`quadrant[dj * nx + di]`), kept by a
    /// kernel that is even in x and in y; `None` for a general kernel.
    pub fn even_quadrant(&self) -> Option<&[f64]> {
        match &self.values {
            SpectrumValues::Even { quadrant, .. } => Some(quadrant),
            SpectrumValues::General(_) => None,
        }
    }

    /// The kernel value at zero offset.
    pub fn self_coefficient(&self) -> f64 {
        self.self_coefficient
    }

    /// The constant the kernel was lowered by (a line contact's datum, see the
    /// field); 0 unless set by [`Self::with_datum_shift`].
    pub fn datum_shift(&self) -> f64 {
        self.datum_shift
    }

    /// The same spectrum recording that its kernel was lowered by `shift`.
    pub fn with_datum_shift(mut self, shift: f64) -> Self {
        self.datum_shift = shift;
        self
    }
}

/// Scratch for one plan: the transforms of one operation at a time, split over the
/// lanes of [`Parallelism::Rayon`].
pub struct Convolver {
    plan: Arc<ConvolutionPlan>,
    /// Half-spectrum rows of the padded field (row-major, `nx + 1` per row, `ny` rows).
    rows: Vec<Complex<f64>>,
    /// The rows `first..last` of the field that hold data (the others are zero and
    /// their spectra in `rows` are not written).
    data_rows: (usize, usize),
    /// Column-major spectrum (`nx + 1` columns of `2 ny`) of [`Self::transform_field`].
    columns: Vec<Complex<f64>>,
    /// Spectrum of the last forward transform, kept for several kernels.
    field_spectrum: Vec<Complex<f64>>,
    /// Each lane's columns of the product's half-spectrum after the column stage,
    /// row-major (`ny` rows of the lane's width): the inverse row stage reads them
    /// row by row, with no gather across the whole spectrum.
    slabs: Vec<Vec<Complex<f64>>>,
    lanes: Vec<Lane>,
}

/// Scratch of one parallel lane.
struct Lane {
    real: Vec<f64>,
    scratch: Vec<Complex<f64>>,
    /// Up to `block_columns` padded columns being transformed.
    block: Vec<Complex<f64>>,
    /// One half-spectrum row assembled from the slabs.
    row: Vec<Complex<f64>>,
}

/// Bytes of padded columns transformed together: they stay in a core's L2 cache
/// through the forward transform, the product and the inverse.
const COLUMN_BLOCK_BYTES: usize = 1 << 19;
/// Grids with fewer cells are transformed on one thread whatever the parallelism:
/// below this the rayon hand-off costs more than it saves.
pub const PARALLEL_MIN_CELLS: usize = 128 * 128;

impl ConvolutionPlan {
    /// Plans the DC-FFT for fields of `nx x ny` cells; a grid without cells is an
    /// [`Error::InvalidValue`] naming `nx` or `ny`.
    pub fn new(nx: usize, ny: usize, parallelism: Parallelism) -> Result<Arc<Self>> {
        for (name, n) in [("nx", nx), ("ny", ny)] {
            if n == 0 {
                return Err(Error::invalid(name, n, "at least 1 cell"));
            }
        }
        Ok(Self::padded(nx, ny, [2 * nx, 2 * ny], parallelism))
    }

    /// [`Self::new`] for the crate's grids, which have cells.
    pub(crate) fn for_grid(nx: usize, ny: usize, parallelism: Parallelism) -> Arc<Self> {
        debug_assert!(nx > 0 && ny > 0);
        Self::padded(nx, ny, [2 * nx, 2 * ny], parallelism)
    }

    /// Plans the DC-FFT for fields of `nx x ny` cells on a `px x py` wrap-around
    /// grid (even sizes, `n <= p <= 2n`, which the callers' paddings are): exact for
    /// fields whose support the padding [`holds`](Self::holds), with even kernels only.
    pub(crate) fn padded(
        nx: usize,
        ny: usize,
        [px, py]: [usize; 2],
        parallelism: Parallelism,
    ) -> Arc<Self> {
        assert!(
            px % 2 == 0
                && py % 2 == 0
                && (nx..=2 * nx).contains(&px)
                && (ny..=2 * ny).contains(&py),
            "padding {px} x {py} for {nx} x {ny} cells"
        );
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        Arc::new(ConvolutionPlan {
            nx,
            ny,
            px,
            py,
            row_forward: real.plan_fft_forward(px),
            row_inverse: real.plan_fft_inverse(px),
            column_forward: complex.plan_fft_forward(py),
            column_inverse: complex.plan_fft_inverse(py),
            parallelism,
        })
    }

    /// The wrap-around grid's size.
    pub fn padding(&self) -> [usize; 2] {
        [self.px, self.py]
    }

    /// Whether the transforms may use the rayon pool.
    pub fn parallelism(&self) -> Parallelism {
        self.parallelism
    }

    /// Whether this plan's padding keeps the DC-FFT exact for a field with `support`
    /// (with an even kernel).
    pub(crate) fn holds(&self, support: &Support) -> bool {
        self.px >= needed_padding(self.nx, support.columns)
            && self.py >= needed_padding(self.ny, support.rows)
    }

    /// Lanes a transform is split into: one below [`PARALLEL_MIN_CELLS`] or when
    /// sequential, else the current rayon pool's threads.
    fn lanes(&self) -> usize {
        match self.parallelism {
            Parallelism::Rayon if self.nx * self.ny >= PARALLEL_MIN_CELLS => {
                rayon::current_num_threads().max(1)
            }
            _ => 1,
        }
    }

    /// Cells along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Cells along y.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Full forward transform of a padded `px x rows` real array (rows beyond
    /// `rows` are zero); returns the column-major spectrum. Rows, then columns, are
    /// split over the pool like the other stages.
    fn forward_padded(&self, padded: &[f64], rows: usize) -> Vec<Complex<f64>> {
        let plan = self;
        let (width, half, py) = (plan.px, plan.px / 2 + 1, plan.py);
        let min_len = if self.lanes() == 1 { usize::MAX } else { 1 };
        let scratch_len = self.scratch_len();
        let mut spectrum_rows = vec![Complex::default(); half * rows];
        spectrum_rows
            .par_chunks_mut(half)
            .zip(padded.par_chunks(width))
            .with_min_len(min_len)
            .for_each_init(
                || (vec![0.0; width], vec![Complex::default(); scratch_len]),
                |(real, scratch), (dst, src)| {
                    real.copy_from_slice(src);
                    plan.row_forward
                        .process_with_scratch(real, dst, scratch)
                        .expect("row FFT lengths are fixed by the plan");
                },
            );
        let mut columns = vec![Complex::default(); half * py];
        columns
            .par_chunks_mut(py)
            .enumerate()
            .with_min_len(min_len)
            .for_each_init(
                || vec![Complex::default(); scratch_len],
                |scratch, (c, col)| {
                    for (r, v) in col[..rows].iter_mut().enumerate() {
                        *v = spectrum_rows[r * half + c];
                    }
                    plan.column_forward.process_with_scratch(col, scratch);
                },
            );
        columns
    }

    /// Scratch an FFT of this plan needs.
    fn scratch_len(&self) -> usize {
        self.row_forward
            .get_scratch_len()
            .max(self.row_inverse.get_scratch_len())
            .max(self.column_forward.get_inplace_scratch_len())
            .max(self.column_inverse.get_inplace_scratch_len())
    }

    /// Scratch for one thread of work.
    pub fn convolver(self: &Arc<Self>) -> Convolver {
        let lanes = self.lanes();
        let scratch_len = self.scratch_len();
        let (half, py) = (self.px / 2 + 1, self.py);
        let per_lane = half.div_ceil(lanes);
        Convolver {
            plan: Arc::clone(self),
            rows: zeroed(half * self.ny, lanes > 1),
            data_rows: (0, self.ny),
            columns: Vec::new(),
            field_spectrum: Vec::new(),
            slabs: (0..lanes)
                .map(|t| {
                    let width = half.saturating_sub(t * per_lane).min(per_lane);
                    zeroed(width * self.ny, lanes > 1)
                })
                .collect(),
            lanes: (0..lanes)
                .map(|_| Lane {
                    real: vec![0.0; self.px],
                    scratch: vec![Complex::default(); scratch_len],
                    block: vec![Complex::default(); self.block_columns() * py],
                    row: vec![Complex::default(); half],
                })
                .collect(),
        }
    }

    /// Padded columns transformed together: [`COLUMN_BLOCK_BYTES`] of them, at least
    /// 4 (one cache line of each row) and at most 16.
    fn block_columns(&self) -> usize {
        (COLUMN_BLOCK_BYTES / (self.py * std::mem::size_of::<Complex<f64>>())).clamp(4, 16)
    }

    /// The spectrum of a kernel given as a function of the cell offset
    /// `(di, dj)` in cells, `-nx < di < nx`, `-ny < dj < ny`. It needs the full
    /// padding of [`Self::new`]; on a plan trimmed for even kernels it is an
    /// [`Error::InvalidValue`].
    pub fn kernel_spectrum(
        self: &Arc<Self>,
        kernel: impl Fn(i64, i64) -> f64 + Sync,
    ) -> Result<KernelSpectrum> {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        if [px, py] != [2 * nx, 2 * ny] {
            return Err(Error::invalid(
                "plan padding",
                format!("{px} x {py}"),
                &format!(
                    "{} x {}: a kernel with no symmetry needs the full padding",
                    2 * nx,
                    2 * ny
                ),
            ));
        }
        Ok(self.offsets_spectrum(kernel))
    }

    /// [`Self::kernel_spectrum`] on the crate's full plans.
    pub(crate) fn offsets_spectrum(
        self: &Arc<Self>,
        kernel: impl Fn(i64, i64) -> f64 + Sync,
    ) -> KernelSpectrum {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        debug_assert_eq!([px, py], [2 * nx, 2 * ny]);
        // Kernel on the wrap-around grid; offset nx (or ny) is never used by a pair
        // of cells and stays zero.
        let mut wrapped = vec![0.0; px * py];
        wrapped.par_chunks_mut(px).enumerate().for_each(|(r, row)| {
            let Some(dj) = wrapped_offset(r, py, ny) else {
                return;
            };
            for (c, v) in row.iter_mut().enumerate() {
                if let Some(di) = wrapped_offset(c, px, nx) {
                    *v = kernel(di, dj);
                }
            }
        });
        self.spectrum_of_wrapped(wrapped)
    }

    /// The spectrum of a kernel that is even in x and in y, given on one quadrant:
    /// `quadrant[dj * nx + di]` for `0 <= di < nx`, `0 <= dj < ny`.
    #[cfg(test)]
    pub(crate) fn even_kernel_spectrum(self: &Arc<Self>, quadrant: &[f64]) -> KernelSpectrum {
        self.even_spectrum_of(Arc::new(quadrant.to_vec()))
    }

    /// An even kernel given by its quadrant only (as [`Self::even_kernel_spectrum`]
    /// takes it): nothing is transformed until a product builds its
    /// spectrum on a padding (the same bits as building it at once). A contact
    /// operator whose products are all on a trimmed padding never needs the full
    /// one. A quadrant of another size than the plan's `nx * ny` cells is an error.
    pub fn even_kernel(self: &Arc<Self>, quadrant: Vec<f64>) -> Result<KernelSpectrum> {
        if quadrant.len() != self.nx * self.ny {
            return Err(Error::invalid(
                "kernel quadrant",
                format!("{} values", quadrant.len()),
                &format!(
                    "{} values, one per cell of the plan's {} x {} grid",
                    self.nx * self.ny,
                    self.nx,
                    self.ny
                ),
            ));
        }
        Ok(KernelSpectrum {
            nx: self.nx,
            ny: self.ny,
            px: self.px,
            py: self.py,
            self_coefficient: quadrant[0],
            datum_shift: 0.0,
            values: SpectrumValues::Even {
                values: None,
                quadrant: Arc::new(quadrant),
            },
        })
    }

    /// The spectrum on this plan's padding of the even kernel that `kernel` was
    /// built from (on a plan of the same grid, the callers' invariant).
    pub(crate) fn respectrum(self: &Arc<Self>, kernel: &KernelSpectrum) -> KernelSpectrum {
        assert!(
            kernel.nx == self.nx && kernel.ny == self.ny,
            "kernel of another grid"
        );
        match &kernel.values {
            SpectrumValues::Even { quadrant, .. } => self.even_spectrum_of(Arc::clone(quadrant)),
            SpectrumValues::General(_) => panic!("only an even kernel has a trimmed padding"),
        }
    }

    fn even_spectrum_of(self: &Arc<Self>, quadrant: Arc<Vec<f64>>) -> KernelSpectrum {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        assert_eq!(
            quadrant.len(),
            nx * ny,
            "quadrant size does not match the plan"
        );
        let mut wrapped = vec![0.0; px * py];
        wrapped.par_chunks_mut(px).enumerate().for_each(|(r, row)| {
            let Some(dj) = wrapped_offset(r, py, ny) else {
                return;
            };
            let src = &quadrant[dj.unsigned_abs() as usize * nx..][..nx];
            for (c, v) in row.iter_mut().enumerate() {
                if let Some(di) = wrapped_offset(c, px, nx) {
                    *v = src[di.unsigned_abs() as usize];
                }
            }
        });
        let general = self.spectrum_of_wrapped(wrapped);
        let SpectrumValues::General(values) = &general.values else {
            unreachable!("a wrapped kernel's spectrum is general")
        };
        // The spectrum of an even real kernel is real and even: keep the real parts
        // of the first py/2 + 1 rows (the imaginary parts are rounding residue).
        let hy = py / 2 + 1;
        let min_len = if self.lanes() == 1 { usize::MAX } else { 1 };
        let even: Vec<f64> = values
            .par_chunks_exact(py)
            .with_min_len(min_len)
            .flat_map_iter(|col| col[..hy].iter().map(|v| v.re))
            .collect();
        KernelSpectrum {
            values: SpectrumValues::Even {
                values: Some(even),
                quadrant,
            },
            ..general
        }
    }

    /// The spectrum of the periodic operator (period: this plan's padding) that
    /// multiplies the Fourier mode `exp(i (xi_x i + xi_y j))` of a field by
    /// `symbol(xi_x, xi_y)`, the wavenumbers in radians per cell (`0 <= xi_x <= pi`,
    /// `-pi < xi_y <= pi`; the modes of negative `xi_x` get the conjugate, as a real
    /// operator's do). Built from the values, with no transform.
    pub(crate) fn symbol_spectrum(
        self: &Arc<Self>,
        symbol: impl Fn(f64, f64) -> Complex<f64> + Sync,
    ) -> KernelSpectrum {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        let scale = 1.0 / (px * py) as f64;
        let two_pi = 2.0 * std::f64::consts::PI;
        let mut values = vec![Complex::default(); (px / 2 + 1) * py];
        values.par_chunks_mut(py).enumerate().for_each(|(c, col)| {
            let xi_x = two_pi * c as f64 / px as f64;
            for (r, v) in col.iter_mut().enumerate() {
                let row = if 2 * r <= py {
                    r as f64
                } else {
                    r as f64 - py as f64
                };
                *v = symbol(xi_x, two_pi * row / py as f64) * scale;
            }
        });
        // The value at zero offset: the mean of the symbol over every mode (the
        // columns 1..px/2 stand for their conjugates too).
        let self_coefficient = values
            .chunks_exact(py)
            .enumerate()
            .map(|(c, col)| {
                let weight = if c == 0 || 2 * c == px { 1.0 } else { 2.0 };
                weight * col.iter().map(|v| v.re).sum::<f64>()
            })
            .sum();
        KernelSpectrum {
            nx,
            ny,
            px,
            py,
            values: SpectrumValues::General(values),
            self_coefficient,
            datum_shift: 0.0,
        }
    }

    fn spectrum_of_wrapped(self: &Arc<Self>, wrapped: Vec<f64>) -> KernelSpectrum {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        let self_coefficient = wrapped[0];
        let mut values = self.forward_padded(&wrapped, py);
        let scale = 1.0 / (px * py) as f64;
        let min_len = if self.lanes() == 1 { usize::MAX } else { 1 };
        values
            .par_chunks_mut(py)
            .with_min_len(min_len)
            .for_each(|col| col.iter_mut().for_each(|v| *v *= scale));
        KernelSpectrum {
            nx,
            ny,
            px,
            py,
            values: SpectrumValues::General(values),
            self_coefficient,
            datum_shift: 0.0,
        }
    }
}

/// Where a field is not zero: the columns `columns.0..columns.1` of the rows
/// `rows.0..rows.1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Support {
    /// First column holding data and one past the last.
    pub(crate) columns: (usize, usize),
    /// First row holding data and one past the last.
    pub(crate) rows: (usize, usize),
}

impl Support {
    /// The support of an `nx x ny` row-major field; `None` if it is zero.
    pub(crate) fn of(field: &[f64], nx: usize, ny: usize) -> Option<Support> {
        debug_assert_eq!(field.len(), nx * ny, "field size does not match the grid");
        let mut support: Option<Support> = None;
        for (j, row) in field.chunks_exact(nx).enumerate() {
            let Some(first) = row.iter().position(|&v| v != 0.0) else {
                continue;
            };
            let last = row.iter().rposition(|&v| v != 0.0).map_or(first, |k| k + 1);
            support = Some(match support {
                None => Support {
                    columns: (first, last),
                    rows: (j, j + 1),
                },
                Some(s) => Support {
                    columns: (s.columns.0.min(first), s.columns.1.max(last)),
                    rows: (s.rows.0, j + 1),
                },
            });
        }
        support
    }

    /// The support widened by `margin` cells on every side, within the grid.
    pub(crate) fn widened(&self, margin: usize, nx: usize, ny: usize) -> Support {
        Support {
            columns: (
                self.columns.0.saturating_sub(margin),
                (self.columns.1 + margin).min(nx),
            ),
            rows: (
                self.rows.0.saturating_sub(margin),
                (self.rows.1 + margin).min(ny),
            ),
        }
    }
}

/// The shortest even wrap-around length on an axis of `n` cells that keeps the
/// DC-FFT of an even kernel exact for data in the cells `first..last` and output in
/// every cell: no pair of an output and a data cell is more than half the length
/// apart (the wrap holds the offsets up to `p/2` both ways), and the output fits.
/// The full padding `2n` holds any data.
pub(crate) fn needed_padding(n: usize, (first, last): (usize, usize)) -> usize {
    let reach = (n - 1 - first.min(n - 1)).max(last.saturating_sub(1));
    (2 * reach).max(n).next_multiple_of(2)
}

/// The padding an FFT does fastest among lengths of at least `needed`: the next
/// `m * 2^a` with an odd part `m` of 1, 3, 5, 7, 9, 25 or 27, at most `2n`. Measured
/// (a 512² grid's DC-FFT on paddings 768 to 1024): these cost 1.04-1.22 times a
/// power of two's time per padded cell, 13 * 2^a 1.57 times; the same at 256² and
/// 1024².
pub(crate) fn quick_padding(needed: usize, n: usize) -> usize {
    let quick = [1, 3, 5, 7, 9, 25, 27]
        .into_iter()
        .map(|m| {
            let mut p = 2 * m;
            while p < needed {
                p *= 2;
            }
            p
        })
        .min()
        .unwrap_or(2 * n);
    quick.min(2 * n)
}

/// A zeroed buffer of `n` values, written by the pool's threads when `parallel`:
/// the first touch of fresh pages is much of a large convolver's set-up.
fn zeroed(n: usize, parallel: bool) -> Vec<Complex<f64>> {
    if parallel {
        let mut v = Vec::with_capacity(n);
        v.par_extend(rayon::iter::repeat_n(Complex::default(), n));
        v
    } else {
        vec![Complex::default(); n]
    }
}

/// Offset in cells of index `k` of a wrap-around axis of `p` (even) entries for `n`
/// cells: `k` up to `p/2`, then `k - p`; `None` where no pair of cells is that far
/// apart (offset `n` and beyond), which stays zero. On the full padding (`p = 2n`)
/// that is the middle entry; on a trimmed one the middle entry `p/2` serves both
/// `+p/2` and `-p/2`, which an even kernel does not tell apart.
fn wrapped_offset(k: usize, p: usize, n: usize) -> Option<i64> {
    let offset = if k <= p / 2 {
        k as i64
    } else {
        k as i64 - p as i64
    };
    (offset.unsigned_abs() < n as u64).then_some(offset)
}

impl Convolver {
    /// The plan this scratch belongs to.
    pub fn plan(&self) -> &Arc<ConvolutionPlan> {
        &self.plan
    }

    /// `out = kernel (*) field`, both `nx x ny` row-major. A kernel of another grid
    /// or padding, one given by its quadrant only ([`ConvolutionPlan::even_kernel`]:
    /// its spectrum is built by the operator that uses it), or a `field` or `out` of
    /// another length than the plan's cells is an [`Error::InvalidValue`] naming it.
    pub fn apply(&mut self, kernel: &KernelSpectrum, field: &[f64], out: &mut [f64]) -> Result<()> {
        self.check_sizes(kernel, field.len(), out.len())?;
        self.convolve(kernel, field, out);
        Ok(())
    }

    /// [`Self::apply`] for the crate's operators, whose sizes are the plan's.
    pub(crate) fn convolve(&mut self, kernel: &KernelSpectrum, field: &[f64], out: &mut [f64]) {
        debug_assert!(self.check_sizes(kernel, field.len(), out.len()).is_ok());
        self.row_stage_forward(field);
        self.column_stage(ColumnWork::Convolve(kernel));
        self.row_stage_inverse(out);
    }

    /// Forward-transforms a field once, for several [`Self::apply_to_transformed`];
    /// a field of another length than the plan's cells is an [`Error::InvalidValue`].
    pub fn transform_field(&mut self, field: &[f64]) -> Result<()> {
        check_length("field", field.len(), self.plan.nx * self.plan.ny)?;
        self.transform(field);
        Ok(())
    }

    /// [`Self::transform_field`] for the crate's fields, whose length is the plan's.
    pub(crate) fn transform(&mut self, field: &[f64]) {
        let plan = Arc::clone(&self.plan);
        debug_assert_eq!(field.len(), plan.nx * plan.ny);
        self.columns
            .resize((plan.px / 2 + 1) * plan.py, Complex::default());
        self.row_stage_forward(field);
        self.column_stage(ColumnWork::Forward);
        std::mem::swap(&mut self.field_spectrum, &mut self.columns);
    }

    /// `out = kernel (*) field` for the field last given to [`Self::transform_field`];
    /// errors as [`Self::apply`], and before any field was transformed.
    pub fn apply_to_transformed(&mut self, kernel: &KernelSpectrum, out: &mut [f64]) -> Result<()> {
        // The field was checked by `transform_field`.
        self.check_sizes(kernel, self.plan.nx * self.plan.ny, out.len())?;
        if self.field_spectrum.is_empty() {
            return Err(Error::invalid(
                "field",
                "none transformed",
                "a field given to transform_field first",
            ));
        }
        self.multiply_transformed(kernel, out);
        Ok(())
    }

    /// [`Self::apply_to_transformed`] for the crate's kernels and outputs, after
    /// [`Self::transform`].
    pub(crate) fn multiply_transformed(&mut self, kernel: &KernelSpectrum, out: &mut [f64]) {
        debug_assert!(self
            .check_sizes(kernel, self.plan.nx * self.plan.ny, out.len())
            .is_ok());
        debug_assert!(!self.field_spectrum.is_empty());
        self.column_stage(ColumnWork::Multiply(kernel));
        self.row_stage_inverse(out);
    }

    fn check_sizes(&self, kernel: &KernelSpectrum, field: usize, out: usize) -> Result<()> {
        let plan = &self.plan;
        let grid = |nx: usize, ny: usize, px: usize, py: usize| {
            format!("{nx} x {ny} cells padded to {px} x {py}")
        };
        if [kernel.nx, kernel.ny, kernel.px, kernel.py] != [plan.nx, plan.ny, plan.px, plan.py] {
            return Err(Error::invalid(
                "kernel",
                grid(kernel.nx, kernel.ny, kernel.px, kernel.py),
                &format!(
                    "a spectrum on this plan's {}",
                    grid(plan.nx, plan.ny, plan.px, plan.py)
                ),
            ));
        }
        if !kernel.has_values() {
            return Err(Error::invalid(
                "kernel",
                "a quadrant without its spectrum",
                "a spectrum (ConvolutionPlan::kernel_spectrum)",
            ));
        }
        let cells = plan.nx * plan.ny;
        check_length("field", field, cells)?;
        check_length("out", out, cells)
    }

    /// Real-to-complex transforms of the field's rows, zero-padded to `2 nx`. Rows
    /// before the first and after the last that hold data (outside the contact) have
    /// zero spectra: they are neither transformed nor written, and the column stage
    /// pads them with zeros.
    fn row_stage_forward(&mut self, field: &[f64]) {
        let plan = &self.plan;
        let (nx, half) = (plan.nx, plan.px / 2 + 1);
        let holds_data = |j: usize| field[j * nx..(j + 1) * nx].iter().any(|&v| v != 0.0);
        let first = (0..plan.ny).find(|&j| holds_data(j)).unwrap_or(plan.ny);
        let last = (first..plan.ny)
            .rev()
            .find(|&j| holds_data(j))
            .map_or(first, |j| j + 1);
        self.data_rows = (first, last);
        let per_lane = (last - first).div_ceil(self.lanes.len()).max(1);
        let process = |first_row: usize, dst_rows: &mut [Complex<f64>], lane: &mut Lane| {
            for (k, dst) in dst_rows.chunks_exact_mut(half).enumerate() {
                let j = first_row + k;
                let src = &field[j * nx..(j + 1) * nx];
                if src.iter().all(|&v| v == 0.0) {
                    dst.fill(Complex::default());
                    continue;
                }
                lane.real[..nx].copy_from_slice(src);
                lane.real[nx..].fill(0.0);
                plan.row_forward
                    .process_with_scratch(&mut lane.real, dst, &mut lane.scratch)
                    .expect("row FFT lengths are fixed by the plan");
            }
        };
        let data = &mut self.rows[first * half..last * half];
        if self.lanes.len() == 1 {
            process(first, data, &mut self.lanes[0]);
        } else {
            data.par_chunks_mut(per_lane * half)
                .zip(self.lanes.par_iter_mut())
                .enumerate()
                .for_each(|(t, (dst, lane))| process(first + t * per_lane, dst, lane));
        }
    }

    /// The column stage, each lane on its own run of columns, a cache-sized block
    /// of them at a time: gathers the block from the row spectra (zero outside the
    /// rows holding data and in the padding) and transforms it forward into the kept
    /// spectrum; or gathers, transforms, multiplies by a kernel and transforms back;
    /// or multiplies the kept spectrum by a kernel and transforms back. A product's
    /// first `ny` rows go to the lane's slab, row-major.
    fn column_stage(&mut self, work: ColumnWork<'_>) {
        let plan = &self.plan;
        let (ny, py, half) = (plan.ny, plan.py, plan.px / 2 + 1);
        let lanes = self.lanes.len();
        let per_lane = half.div_ceil(lanes);
        let block_columns = plan.block_columns();
        let (first_row, last_row) = self.data_rows;
        let rows = &self.rows;
        let field_spectrum = &self.field_spectrum;
        // Gathers columns c0.. of the row spectra into `block` (`py` per column).
        let gather = |c0: usize, block: &mut [Complex<f64>]| {
            let width = block.len() / py;
            for col in block.chunks_exact_mut(py) {
                col[..first_row].fill(Complex::default());
                col[last_row..].fill(Complex::default());
            }
            for r in first_row..last_row {
                let src = &rows[r * half + c0..][..width];
                for (q, v) in src.iter().enumerate() {
                    block[q * py + r] = *v;
                }
            }
        };
        if let ColumnWork::Forward = work {
            let process = |first_column: usize, cols: &mut [Complex<f64>], lane: &mut Lane| {
                for (b, block) in cols.chunks_mut(block_columns * py).enumerate() {
                    gather(first_column + b * block_columns, block);
                    plan.column_forward
                        .process_with_scratch(block, &mut lane.scratch);
                }
            };
            if lanes == 1 {
                process(0, &mut self.columns, &mut self.lanes[0]);
            } else {
                self.columns
                    .par_chunks_mut(per_lane * py)
                    .zip(self.lanes.par_iter_mut())
                    .enumerate()
                    .for_each(|(t, (cols, lane))| process(t * per_lane, cols, lane));
            }
            return;
        }
        let process = |first_column: usize, slab: &mut [Complex<f64>], lane: &mut Lane| {
            let width_of_lane = slab.len() / ny;
            for c0 in (first_column..first_column + width_of_lane).step_by(block_columns) {
                let width = block_columns.min(first_column + width_of_lane - c0);
                let block = &mut lane.block[..width * py];
                match work {
                    ColumnWork::Convolve(kernel) => {
                        gather(c0, block);
                        plan.column_forward
                            .process_with_scratch(block, &mut lane.scratch);
                        kernel.multiply_columns(c0, block, None);
                    }
                    ColumnWork::Multiply(kernel) => {
                        let kept = &field_spectrum[c0 * py..][..width * py];
                        kernel.multiply_columns(c0, block, Some(kept));
                    }
                    ColumnWork::Forward => unreachable!("handled above"),
                }
                plan.column_inverse
                    .process_with_scratch(block, &mut lane.scratch);
                // The first ny rows of the block into the slab, a row at a time.
                let offset = c0 - first_column;
                for (r, dst) in slab.chunks_exact_mut(width_of_lane).enumerate() {
                    for (q, v) in dst[offset..offset + width].iter_mut().enumerate() {
                        *v = block[q * py + r];
                    }
                }
            }
        };
        if lanes == 1 {
            process(0, &mut self.slabs[0], &mut self.lanes[0]);
        } else {
            self.slabs
                .par_iter_mut()
                .zip(self.lanes.par_iter_mut())
                .enumerate()
                .for_each(|(t, (slab, lane))| process(t * per_lane, slab, lane));
        }
    }

    /// Complex-to-real transforms of the product's first `ny` rows, each assembled
    /// from the lanes' slabs; the padding rows are not computed.
    fn row_stage_inverse(&mut self, out: &mut [f64]) {
        let plan = &self.plan;
        let nx = plan.nx;
        let per_lane = plan.ny.div_ceil(self.lanes.len());
        let slabs = &self.slabs;
        let process = |first_row: usize, dst_rows: &mut [f64], lane: &mut Lane| {
            for (k, dst) in dst_rows.chunks_exact_mut(nx).enumerate() {
                let r = first_row + k;
                let mut c = 0;
                for slab in slabs {
                    let width = slab.len() / plan.ny;
                    lane.row[c..c + width].copy_from_slice(&slab[r * width..][..width]);
                    c += width;
                }
                // The first and last bins of a real signal's spectrum are real;
                // drop the rounding residue so realfft accepts them.
                let last = lane.row.len() - 1;
                lane.row[0].im = 0.0;
                lane.row[last].im = 0.0;
                plan.row_inverse
                    .process_with_scratch(&mut lane.row, &mut lane.real, &mut lane.scratch)
                    .expect("row FFT lengths are fixed by the plan");
                dst.copy_from_slice(&lane.real[..nx]);
            }
        };
        if self.lanes.len() == 1 {
            process(0, out, &mut self.lanes[0]);
        } else {
            out.par_chunks_mut(per_lane * nx)
                .zip(self.lanes.par_iter_mut())
                .enumerate()
                .for_each(|(t, (dst, lane))| process(t * per_lane, dst, lane));
        }
    }
}

/// What the column stage does after gathering.
/// A slice of `len` values where the plan has `cells`: an error naming `name`.
fn check_length(name: &str, len: usize, cells: usize) -> Result<()> {
    if len == cells {
        Ok(())
    } else {
        Err(Error::invalid(
            name,
            format!("{len} values"),
            &format!("{cells} values, one per cell of the plan's grid"),
        ))
    }
}

#[derive(Clone, Copy)]
enum ColumnWork<'a> {
    /// Forward transform only (the field spectrum is kept).
    Forward,
    /// Forward, times the kernel, inverse.
    Convolve(&'a KernelSpectrum),
    /// The kept field spectrum times the kernel, inverse.
    Multiply(&'a KernelSpectrum),
}

/// `out += K δ` by direct summation, for a kernel even in x and in y given by its
/// quadrant (`quadrant[dj * nx + di] = K(di, dj)`, as [`ConvolutionPlan::even_kernel`]
/// takes it) and a field `δ` that is non-zero on a few `cells` only (`(index,
/// value)` with row-major indices): `cells.len() * nx * ny` multiply-adds, fewer than
/// a DC-FFT's work for a handful of cells (a contact solver's correction where a
/// step was projected). Each output cell adds the cells' terms in their order, so
/// the bits do not depend on `parallelism`.
pub(crate) fn add_sparse_even_convolution(
    nx: usize,
    ny: usize,
    quadrant: &[f64],
    cells: &[(usize, f64)],
    out: &mut [f64],
    parallelism: Parallelism,
) {
    // The operator's sparse updates: the solvers' cells on the operator's grid.
    debug_assert!(quadrant.len() == nx * ny && out.len() == nx * ny);
    debug_assert!(cells.iter().all(|&(k, _)| k < nx * ny));
    let add_row = |j: usize, row: &mut [f64]| {
        for &(index, value) in cells {
            let (column, data_row) = (index % nx, index / nx);
            let kernel = &quadrant[j.abs_diff(data_row) * nx..][..nx];
            // Output columns from `column` on are offsets 0, 1, ..; those before it
            // are offsets `column` down to 1.
            let (before, after) = row.split_at_mut(column);
            after
                .iter_mut()
                .zip(kernel)
                .for_each(|(o, k)| *o += value * k);
            before
                .iter_mut()
                .zip(kernel[1..=column].iter().rev())
                .for_each(|(o, k)| *o += value * k);
        }
    };
    // Rows split over the pool as the solvers' passes split them.
    let passes = crate::passes::Passes::new(nx * ny, parallelism);
    out.par_chunks_mut(nx)
        .with_min_len(passes.min_rows(nx))
        .enumerate()
        .for_each(|(j, row)| add_row(j, row));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A kernel with no symmetry, so that sign or transpose slips show up.
    fn lopsided(di: i64, dj: i64) -> f64 {
        1.0 / (1.0 + (di as f64 - 0.3).powi(2) + 2.0 * (dj as f64 + 0.2).powi(2)) + 0.01 * di as f64
    }

    /// Whether `result` is an [`Error::InvalidValue`] naming `field`.
    fn names<T: std::fmt::Debug>(result: Result<T>, field: &str) -> bool {
        matches!(result, Err(Error::InvalidValue { field: f, .. }) if f == field)
    }

    #[test]
    fn the_public_entry_points_refuse_wrong_sizes_naming_the_argument() {
        assert!(names(
            ConvolutionPlan::new(0, 4, Parallelism::Sequential),
            "nx"
        ));
        assert!(names(ConvolutionPlan::new(4, 0, Parallelism::Rayon), "ny"));
        let plan = ConvolutionPlan::new(6, 5, Parallelism::Sequential).unwrap();
        let kernel = plan.kernel_spectrum(lopsided).unwrap();
        let (field, mut out) = (vec![1.0; 30], vec![0.0; 30]);
        let mut conv = plan.convolver();
        assert!(names(conv.apply(&kernel, &field[1..], &mut out), "field"));
        assert!(names(conv.apply(&kernel, &field, &mut out[1..]), "out"));
        let other = ConvolutionPlan::new(5, 6, Parallelism::Sequential).unwrap();
        let other_kernel = other.kernel_spectrum(lopsided).unwrap();
        assert!(names(conv.apply(&other_kernel, &field, &mut out), "kernel"));
        let quadrant_only = plan.even_kernel(vec![1.0; 30]).unwrap();
        assert!(names(
            conv.apply(&quadrant_only, &field, &mut out),
            "kernel"
        ));
        assert!(names(conv.apply_to_transformed(&kernel, &mut out), "field"));
        assert!(names(conv.transform_field(&field[..29]), "field"));
        conv.transform_field(&field).unwrap();
        assert!(names(
            conv.apply_to_transformed(&kernel, &mut out[..29]),
            "out"
        ));
        // A plan trimmed for even kernels has no room for a kernel without symmetry.
        let trimmed = ConvolutionPlan::padded(6, 5, [8, 6], Parallelism::Sequential);
        assert!(names(trimmed.kernel_spectrum(lopsided), "plan padding"));
        // Nothing was written by a refused call, and the right sizes still work.
        assert!(out.iter().all(|&v| v == 0.0));
        conv.apply(&kernel, &field, &mut out).unwrap();
        let mut slow = vec![0.0; 30];
        thirdbody_reference::direct_convolution(6, 5, lopsided, &field, &mut slow).unwrap();
        for (a, b) in out.iter().zip(&slow) {
            assert!((a - b).abs() < 1e-13 * 30.0);
        }
        let mut cache = crate::KernelCache::new();
        assert!(names(cache.plan(0, 8, Parallelism::Sequential), "nx"));
    }

    #[test]
    fn dc_fft_equals_direct_summation() {
        for &(nx, ny) in &[(8, 8), (9, 12), (16, 10), (13, 7)] {
            for par in [Parallelism::Sequential, Parallelism::Rayon] {
                let plan = ConvolutionPlan::new(nx, ny, par).unwrap();
                let spectrum = plan.kernel_spectrum(lopsided).unwrap();
                let mut conv = plan.convolver();
                let field: Vec<f64> = (0..nx * ny).map(|k| ((k * 37) % 11) as f64 - 4.0).collect();
                let mut fast = vec![0.0; nx * ny];
                let mut slow = vec![0.0; nx * ny];
                conv.apply(&spectrum, &field, &mut fast).unwrap();
                thirdbody_reference::direct_convolution(nx, ny, lopsided, &field, &mut slow)
                    .unwrap();
                let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for k in 0..nx * ny {
                    assert!(
                        (fast[k] - slow[k]).abs() < 1e-12 * scale,
                        "{nx}x{ny} {par:?} {k}"
                    );
                }
                assert_eq!(spectrum.self_coefficient(), lopsided(0, 0));
            }
        }
    }

    #[test]
    fn even_kernel_from_a_quadrant_equals_the_full_kernel() {
        let (nx, ny) = (11, 8);
        let even = |di: i64, dj: i64| 1.0 / (1.0 + (di * di) as f64 + 0.5 * (dj * dj) as f64);
        let plan = ConvolutionPlan::new(nx, ny, Parallelism::Sequential).unwrap();
        let full = plan.kernel_spectrum(even).unwrap();
        let quadrant: Vec<f64> = (0..nx * ny)
            .map(|k| even((k % nx) as i64, (k / nx) as i64))
            .collect();
        let half = plan.even_kernel_spectrum(&quadrant);
        assert_eq!(full.self_coefficient(), half.self_coefficient());
        // The even spectrum is the real part of the full one on its stored rows, and
        // its products equal the full spectrum's and the direct sum's.
        let (
            SpectrumValues::General(f),
            SpectrumValues::Even {
                values: Some(e), ..
            },
        ) = (&full.values, &half.values)
        else {
            panic!("a general and an even spectrum")
        };
        assert_eq!(e.len(), (nx + 1) * (ny + 1));
        for c in 0..=nx {
            for r in 0..2 * ny {
                let mirrored = if r <= ny { r } else { 2 * ny - r };
                let v = f[c * 2 * ny + r];
                assert!((v.re - e[c * (ny + 1) + mirrored]).abs() < 1e-15 * 88.0);
                assert!(
                    v.im.abs() < 1e-15 * 88.0,
                    "an even kernel's spectrum is real"
                );
            }
        }
        let field: Vec<f64> = (0..nx * ny).map(|k| ((k * 13) % 7) as f64 - 3.0).collect();
        let (mut a, mut b, mut d) = (vec![0.0; nx * ny], vec![0.0; nx * ny], vec![0.0; nx * ny]);
        let mut conv = plan.convolver();
        conv.apply(&full, &field, &mut a).unwrap();
        conv.apply(&half, &field, &mut b).unwrap();
        thirdbody_reference::direct_convolution(nx, ny, even, &field, &mut d).unwrap();
        for k in 0..nx * ny {
            assert!(
                (a[k] - b[k]).abs() < 1e-13 && (b[k] - d[k]).abs() < 1e-13,
                "{k}"
            );
        }
    }

    /// An even kernel with a slow decay, so that aliasing across a too-short
    /// padding shows up.
    fn even_slow(di: i64, dj: i64) -> f64 {
        1.0 / (0.5 + ((di * di) as f64 + 1.7 * (dj * dj) as f64).sqrt())
    }

    #[test]
    fn a_symbol_spectrum_is_the_periodic_operator_of_its_symbol() {
        // The symbol 1 + i sin(xi_x) on a 12 x 10 periodic grid is the identity
        // plus half the difference of the next and the previous cell along x (the
        // convention of the kernels' spectra: a kernel K(di) has the symbol
        // sum K(d) exp(-i xi d)).
        let (nx, ny) = (12, 10);
        let plan = ConvolutionPlan::padded(nx, ny, [nx, ny], Parallelism::Sequential);
        let spectrum = plan.symbol_spectrum(|xi_x, _| Complex::new(1.0, xi_x.sin()));
        assert!((spectrum.self_coefficient() - 1.0).abs() < 1e-14);
        let field: Vec<f64> = (0..nx * ny).map(|k| ((k * 7) % 5) as f64 - 2.0).collect();
        let mut out = vec![0.0; nx * ny];
        plan.convolver().apply(&spectrum, &field, &mut out).unwrap();
        for j in 0..ny {
            for i in 0..nx {
                let at = |i: usize| field[j * nx + i % nx];
                // The mode exp(i xi n) times i sin(xi) = (e^{i xi} - e^{-i xi}) / 2 is
                // half its next cell's value minus half its previous one's.
                let expected = at(i) + 0.5 * (at(i + 1) - at(i + nx - 1));
                assert!((out[j * nx + i] - expected).abs() < 1e-13, "({i}, {j})");
            }
        }
    }

    #[test]
    fn needed_padding_is_twice_the_farthest_reach() {
        // Data everywhere: offsets up to n - 1 either way.
        assert_eq!(needed_padding(10, (0, 10)), 18);
        // Centred data in 3..7 of 10 cells: output cell 9 is 6 from data cell 3.
        assert_eq!(needed_padding(10, (3, 7)), 12);
        // One data cell in the middle: the output must still fit.
        assert_eq!(needed_padding(10, (5, 6)), 10);
        // Data at one edge reach the far edge.
        assert_eq!(needed_padding(9, (0, 2)), 16);
        assert_eq!(quick_padding(1669, 1024), 27 * 64);
        assert_eq!(quick_padding(1730, 1024), 7 * 256);
        assert_eq!(quick_padding(790, 512), 25 * 32);
        assert_eq!(quick_padding(1500, 1024), 1536);
        assert_eq!(quick_padding(2047, 1024), 2048);
        assert_eq!(quick_padding(130, 64), 128);
    }

    #[test]
    fn a_trimmed_padding_equals_direct_summation_on_the_data_it_holds() {
        // (nx, ny, columns, rows) of the data.
        let cases = [
            (16, 16, (4, 12), (5, 11)),
            (21, 13, (2, 9), (6, 13)),
            (12, 19, (0, 12), (8, 9)),
            (15, 15, (7, 8), (7, 8)),
            (20, 11, (0, 3), (0, 11)),
        ];
        for (nx, ny, columns, rows) in cases {
            let support = Support { columns, rows };
            let quadrant: Vec<f64> = (0..nx * ny)
                .map(|k| even_slow((k % nx) as i64, (k / nx) as i64))
                .collect();
            let full = ConvolutionPlan::new(nx, ny, Parallelism::Sequential).unwrap();
            let kernel = full.even_kernel_spectrum(&quadrant);
            let field: Vec<f64> = (0..nx * ny)
                .map(|k| {
                    let (i, j) = (k % nx, k / nx);
                    let inside =
                        (columns.0..columns.1).contains(&i) && (rows.0..rows.1).contains(&j);
                    if inside {
                        ((k * 37) % 11) as f64 - 4.0
                    } else {
                        0.0
                    }
                })
                .collect();
            assert_eq!(
                Support::of(&field, nx, ny).map(|s| s.rows.0 >= rows.0),
                Some(true)
            );
            let mut direct = vec![0.0; nx * ny];
            thirdbody_reference::direct_convolution(nx, ny, even_slow, &field, &mut direct)
                .unwrap();
            let scale = direct.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let error = |px: usize, py: usize, par: Parallelism| {
                let plan = ConvolutionPlan::padded(nx, ny, [px, py], par);
                let spectrum = plan.respectrum(&kernel);
                let mut out = vec![0.0; nx * ny];
                plan.convolver().apply(&spectrum, &field, &mut out).unwrap();
                out.iter()
                    .zip(&direct)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs() / scale))
            };
            let (px, py) = (needed_padding(nx, columns), needed_padding(ny, rows));
            let plan = ConvolutionPlan::padded(nx, ny, [px, py], Parallelism::Sequential);
            assert!(plan.holds(&support));
            for par in [Parallelism::Sequential, Parallelism::Rayon] {
                assert!(error(px, py, par) < 1e-13, "{nx}x{ny} {support:?} {par:?}");
                let (qx, qy) = (quick_padding(px, nx), quick_padding(py, ny));
                assert!(error(qx, qy, par) < 1e-13, "{nx}x{ny} quick {qx}x{qy}");
            }
            // One step shorter along an axis that was trimmed aliases: the bound is
            // tight, not just safe.
            if px - 2 >= nx {
                assert!(
                    error(px - 2, 2 * ny, Parallelism::Sequential) > 1e-6,
                    "{nx}x{ny} x"
                );
            }
            if py - 2 >= ny {
                assert!(
                    error(2 * nx, py - 2, Parallelism::Sequential) > 1e-6,
                    "{nx}x{ny} y"
                );
            }
        }
    }

    #[test]
    fn a_quadrant_of_the_wrong_size_is_an_error() {
        let plan = ConvolutionPlan::new(13, 9, Parallelism::Sequential).unwrap();
        let e = plan.even_kernel(vec![1.0; 13 * 9 - 1]).unwrap_err();
        let message = e.to_string();
        assert!(message.contains("kernel quadrant"), "{message}");
        assert!(
            message.contains("116 values") && message.contains("117 values"),
            "{message}"
        );
    }

    #[test]
    fn a_kernel_given_by_its_quadrant_gets_the_same_spectrum_when_built() {
        let (nx, ny) = (13, 9);
        let plan = ConvolutionPlan::new(nx, ny, Parallelism::Sequential).unwrap();
        let quadrant: Vec<f64> = (0..nx * ny)
            .map(|k| even_slow((k % nx) as i64, (k / nx) as i64))
            .collect();
        let eager = plan.even_kernel_spectrum(&quadrant);
        let lazy = plan.even_kernel(quadrant.clone()).unwrap();
        assert!(!lazy.has_values() && eager.has_values());
        assert_eq!(lazy.self_coefficient(), eager.self_coefficient());
        assert!(lazy.bytes() < eager.bytes());
        let built = plan.respectrum(&lazy);
        assert_eq!(format!("{built:?}"), format!("{eager:?}"));
    }

    #[test]
    fn one_transform_serves_several_kernels() {
        let (nx, ny) = (10, 9);
        let plan = ConvolutionPlan::new(nx, ny, Parallelism::Rayon).unwrap();
        let a = plan.kernel_spectrum(lopsided).unwrap();
        let b = plan.kernel_spectrum(|i, j| (i * i + j) as f64).unwrap();
        let mut conv = plan.convolver();
        let field: Vec<f64> = (0..nx * ny).map(|k| (k % 7) as f64).collect();
        conv.transform_field(&field).unwrap();
        let (mut oa, mut ob) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        conv.apply_to_transformed(&a, &mut oa).unwrap();
        conv.apply_to_transformed(&b, &mut ob).unwrap();
        let (mut ra, mut rb) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        thirdbody_reference::direct_convolution(nx, ny, lopsided, &field, &mut ra).unwrap();
        thirdbody_reference::direct_convolution(nx, ny, |i, j| (i * i + j) as f64, &field, &mut rb)
            .unwrap();
        for k in 0..nx * ny {
            assert!((oa[k] - ra[k]).abs() < 1e-10 * (1.0 + ra[k].abs()));
            assert!((ob[k] - rb[k]).abs() < 1e-9 * (1.0 + rb[k].abs()));
        }
    }

    #[test]
    fn a_sparse_sum_adds_what_direct_summation_of_its_cells_gives() {
        // Odd and even cell counts, two cells in one row, cells on every edge, and
        // a grid wide enough (128² cells) to be split over the pool's threads.
        for &(nx, ny) in &[(11, 7), (128, 128)] {
            let quadrant: Vec<f64> = (0..nx * ny)
                .map(|k| even_slow((k % nx) as i64, (k / nx) as i64))
                .collect();
            let last = nx * ny - 1;
            let cell_sets: [Vec<(usize, f64)>; 4] = [
                vec![(3 * nx + 4, 0.7)],
                vec![(0, 1.5), (nx - 1, -0.25)],
                vec![(nx + 2, 2.0), (nx + 6, -1.0), (last, 0.5)],
                vec![
                    (2, 0.3),
                    (ny / 2 * nx, 1.1),
                    (ny / 2 * nx + 1, -0.6),
                    (last - 3, 0.9),
                ],
            ];
            for cells in &cell_sets {
                // The kernel at every output cell's offset from each data cell.
                let expected: Vec<f64> = (0..nx * ny)
                    .map(|o| {
                        let (i, j) = ((o % nx) as i64, (o / nx) as i64);
                        cells
                            .iter()
                            .map(|&(k, v)| {
                                let (ci, cj) = ((k % nx) as i64, (k / nx) as i64);
                                v * even_slow(i - ci, j - cj)
                            })
                            .sum()
                    })
                    .collect();
                // Added to what is there.
                let before: Vec<f64> = (0..nx * ny).map(|k| (k % 5) as f64 - 2.0).collect();
                let mut sums = Vec::new();
                for par in [Parallelism::Sequential, Parallelism::Rayon] {
                    let mut out = before.clone();
                    add_sparse_even_convolution(nx, ny, &quadrant, cells, &mut out, par);
                    for k in 0..nx * ny {
                        let added = out[k] - before[k];
                        assert!(
                            (added - expected[k]).abs() < 1e-13 * (1.0 + expected[k].abs()),
                            "{nx}x{ny} {cells:?} cell {k}: {added} against {}",
                            expected[k]
                        );
                    }
                    sums.push(out);
                }
                assert_eq!(sums[0], sums[1], "the same bits on one thread and many");
            }
        }
    }
}
