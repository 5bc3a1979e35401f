//! Subsurface stresses on sections, by discrete convolution of the surface pressure
//! with the stress kernels of one depth at a time (docs/architecture.md (numerics)):
//! `sigma_c(x_i, y, z) = sum_{k,l} K_c(x_i - x_k, y - y_l, z) p_{k,l}`, exact for
//! pressure uniform over each cell.
//!
//! - Whole planes (one depth or a block of depths): 2-D DC-FFT per depth and
//!   component; the pressure is transformed once per thread and each kernel
//!   spectrum multiplies it. Depths run in parallel with one-thread FFTs.
//! - An XZ plane (one row of outputs per depth): the 2-D transform would compute
//!   `ny` times more outputs than wanted, so the row is summed directly over the
//!   loaded source rows, each a 1-D DC-FFT along x: with `P_l` the spectrum of
//!   source row l (computed once), `sigma_c(., y, z) = IFFT(sum_l K_c,l P_l)`. Per
//!   depth that costs one real FFT of length `2 nx` per loaded row and component
//!   instead of a 2-D forward and inverse pair per component. A body may sum a part
//!   of its kernels otherwise ([`StressKernels::fill_row`]): a layered body's
//!   remainder is summed against the pressure's spectrum and moments, and only
//!   Love's kernels and the carriers go through the table.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;

use super::kernels::{InfluenceTable, OffsetLattice, RowSource, StressKernels, COMPONENTS};
use crate::convolution::{ConvolutionPlan, Parallelism};
use crate::grid::Grid;

/// Six component arrays.
pub(crate) type Components = [Vec<f64>; COMPONENTS];

/// Stresses at all cell centres `(x_i, y_j)` of `grid` for each depth:
/// `out[c][(k * ny + j) * nx + i]`.
pub(crate) fn planes(
    grid: &Grid,
    pressure: &[f64],
    kernels: &dyn StressKernels,
    depths: &[f64],
    depth_done: &(dyn Fn() + Sync),
) -> Components {
    let (nx, ny) = (grid.nx, grid.ny);
    let n = nx * ny;
    let lattice = OffsetLattice {
        cell: grid.cell,
        x_first: -(nx as f64 - 1.0),
        cols: 2 * nx - 1,
        y_first: -(ny as f64 - 1.0),
        rows: 2 * ny - 1,
    };
    let one_depth = |plan: &Arc<ConvolutionPlan>,
                     conv: &mut crate::convolution::Convolver,
                     table: &mut InfluenceTable,
                     z: f64| {
        kernels.fill(z, &lattice, table);
        let mut out: Components = Default::default();
        for (c, o) in out.iter_mut().enumerate() {
            let table: &InfluenceTable = table;
            let (cx, cy) = (nx as i64 - 1, ny as i64 - 1);
            let spectrum = plan
                .offsets_spectrum(|di, dj| table.get(c, (di + cx) as usize, (dj + cy) as usize));
            o.resize(n, 0.0);
            conv.multiply_transformed(&spectrum, o);
        }
        out
    };
    let per_depth: Vec<Components> = if depths.len() > 1 {
        let plan = ConvolutionPlan::for_grid(nx, ny, Parallelism::Sequential);
        per_thread_map(
            depths,
            || {
                let mut conv = plan.convolver();
                conv.transform(pressure);
                (conv, InfluenceTable::default())
            },
            |(conv, table), &z| {
                let out = one_depth(&plan, conv, table, z);
                depth_done();
                out
            },
        )
    } else {
        let plan = ConvolutionPlan::for_grid(nx, ny, Parallelism::Rayon);
        let mut conv = plan.convolver();
        conv.transform(pressure);
        let mut table = InfluenceTable::default();
        depths
            .iter()
            .map(|&z| {
                let out = one_depth(&plan, &mut conv, &mut table, z);
                depth_done();
                out
            })
            .collect()
    };
    gather(per_depth, n)
}

/// Stresses along the row `y` (any y; x at the cell centres) for each depth:
/// `out[c][k * nx + i]`.
pub(crate) fn xz_plane(
    grid: &Grid,
    pressure: &[f64],
    kernels: &dyn StressKernels,
    y: f64,
    depths: &[f64],
    depth_done: &(dyn Fn() + Sync),
) -> Components {
    let (nx, ny, h) = (grid.nx, grid.ny, grid.cell);
    let loaded: Vec<usize> = (0..ny)
        .filter(|&l| pressure[l * nx..(l + 1) * nx].iter().any(|&p| p != 0.0))
        .collect();
    let Some(&l_max) = loaded.last() else {
        depths.iter().for_each(|_| depth_done());
        return std::array::from_fn(|_| vec![0.0; nx * depths.len()]);
    };
    // Lattice row m holds the offsets to source row l = l_max - m, in cells. A y
    // within rounding of a row edge is put on it, so that surface stresses there are
    // the mean of both sides rather than one side chosen by rounding; a y within
    // rounding of a row centre is put on it, so that rows at opposite offsets pair.
    let mut y_first = (y - grid.y(l_max)) / h;
    for snap in [y_first.floor() + 0.5, y_first.round()] {
        if (y_first - snap).abs() < 1e-9 {
            y_first = snap;
        }
    }
    let width = 2 * nx;
    let mut planner = RealFftPlanner::<f64>::new();
    let forward = planner.plan_fft_forward(width);
    let inverse = planner.plan_fft_inverse(width);
    let half = nx + 1;
    // Spectra of the loaded source rows, zero-padded to 2 nx, grouped by |offset|.
    let mut groups: Vec<SourceGroup> = Vec::new();
    let mut group_of_offset = std::collections::HashMap::new();
    let parity = kernels.parity_in_y();
    for &l in &loaded {
        let mut real = vec![0.0; width];
        real[..nx].copy_from_slice(&pressure[l * nx..(l + 1) * nx]);
        let mut spec = vec![Complex::default(); half];
        forward
            .process(&mut real, &mut spec)
            .expect("FFT lengths are fixed by the plan");
        let m = l_max - l;
        let t = y_first + m as f64;
        let key = if parity.is_some() {
            t.abs().to_bits()
        } else {
            m as u64
        };
        let g = *group_of_offset.entry(key).or_insert_with(|| {
            groups.push(SourceGroup::default());
            groups.len() - 1
        });
        let slot = if t >= 0.0 {
            &mut groups[g].positive
        } else {
            &mut groups[g].negative
        };
        *slot = Some((m, spec));
    }
    let mut groups: Vec<PairedRows> = groups.into_iter().map(|g| g.paired(half)).collect();
    // Kernels are needed only at the offsets of the groups' kernel rows.
    let m_first = groups.iter().map(|g| g.m).min().unwrap_or(0);
    let m_last = groups.iter().map(|g| g.m).max().unwrap_or(0);
    for g in &mut groups {
        g.m -= m_first;
    }
    let lattice = OffsetLattice {
        cell: h,
        x_first: -(nx as f64 - 1.0),
        cols: 2 * nx - 1,
        y_first: y_first + m_first as f64,
        rows: m_last - m_first + 1,
    };
    // The pressure and the row, for the part of the kernels a body sums against the
    // pressure's spectrum (the row's offset from source row 0 is that of row l_max
    // plus l_max).
    let source = RowSource::new(pressure, nx, ny, y_first + l_max as f64);
    let scratch_len = forward.get_scratch_len().max(inverse.get_scratch_len());
    let scale = 1.0 / width as f64;
    // The body's work shared by the depths is built while the depths' tables are
    // (its own parallel parts leave cores idle that the depths take), and added last.
    let each_depth = || {
        per_thread_map(
            depths,
            || {
                (
                    InfluenceTable::default(),
                    vec![0.0; width],
                    vec![Complex::default(); half],
                    vec![Complex::default(); half],
                    vec![Complex::default(); scratch_len],
                )
            },
            |(table, real, spec, acc, scratch), &z| {
                let mut row: Components = std::array::from_fn(|_| vec![0.0; nx]);
                kernels.fill_row(z, &lattice, table, &source, &mut row);
                let mut out: Components = Default::default();
                for (c, o) in out.iter_mut().enumerate() {
                    acc.fill(Complex::default());
                    let even = parity.is_none_or(|even| even[c]);
                    for group in &groups {
                        let m = group.m;
                        let p_spec = if even { &group.plus } else { &group.minus };
                        let row = &table.values[c][m * lattice.cols..(m + 1) * lattice.cols];
                        // Wrap-around order: offsets 0..nx-1, an unused slot, then
                        // the negative offsets -(nx-1)..-1.
                        real[..nx].copy_from_slice(&row[nx - 1..]);
                        real[nx] = 0.0;
                        real[nx + 1..].copy_from_slice(&row[..nx - 1]);
                        forward
                            .process_with_scratch(real, spec, scratch)
                            .expect("FFT lengths are fixed by the plan");
                        for ((a, k), p) in acc.iter_mut().zip(spec.iter()).zip(p_spec) {
                            *a += k * p;
                        }
                    }
                    acc[0].im = 0.0;
                    acc[nx].im = 0.0;
                    inverse
                        .process_with_scratch(acc, real, scratch)
                        .expect("FFT lengths are fixed by the plan");
                    o.extend(real[..nx].iter().zip(&row[c]).map(|(v, r)| v * scale + r));
                }
                depth_done();
                out
            },
        )
    };
    let (prepared, mut per_depth): (_, Vec<Components>) = rayon::join(
        || kernels.prepare_row(&lattice, &source, depths),
        each_depth,
    );
    if let Some(prepared) = &prepared {
        for (out, &z) in per_depth.iter_mut().zip(depths) {
            kernels.add_prepared_row(z, prepared, out);
        }
    }
    gather(per_depth, nx)
}

/// `f(state, item)` for every item, in parallel, in order: one state from `init`
/// per thread, kept for all of its items (a kernel table keeps work between the
/// depths of one lattice). Each thread takes the next item not yet taken, so that an
/// item far costlier than the others (a depth whose remainder needs many aliases)
/// does not leave the other threads idle at the end. Rayon's `map_init` makes a
/// state per split job, several per thread.
pub(super) fn per_thread_map<T: Sync, S, R: Send>(
    items: &[T],
    init: impl Fn() -> S + Sync,
    f: impl Fn(&mut S, &T) -> R + Sync,
) -> Vec<R> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let tasks = rayon::current_num_threads().clamp(1, items.len().max(1));
    let next = AtomicUsize::new(0);
    let parts: Vec<Vec<(usize, R)>> = (0..tasks)
        .into_par_iter()
        .map(|_| {
            let mut state = init();
            let mut done = Vec::new();
            loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(item) = items.get(i) else {
                    break done;
                };
                done.push((i, f(&mut state, item)));
            }
        })
        .collect();
    let mut slots: Vec<Option<R>> = std::iter::repeat_with(|| None).take(items.len()).collect();
    for (i, r) in parts.into_iter().flatten() {
        slots[i] = Some(r);
    }
    slots
        .into_iter()
        .map(|r| r.expect("one result per item"))
        .collect()
}

/// The loaded source rows at offsets `+t` and `-t` (either may be absent).
#[derive(Default)]
struct SourceGroup {
    positive: Option<(usize, Vec<Complex<f64>>)>,
    negative: Option<(usize, Vec<Complex<f64>>)>,
}

/// One kernel row (lattice row `m`, offset t) serving the source rows at +-t:
/// with `K(-t) = K(t)` the rows contribute `K(t) plus`, with `K(-t) = -K(t)`,
/// `K(t) minus`.
struct PairedRows {
    m: usize,
    plus: Vec<Complex<f64>>,
    minus: Vec<Complex<f64>>,
}

impl SourceGroup {
    fn paired(self, half: usize) -> PairedRows {
        let zero = vec![Complex::default(); half];
        let (m, same, opposite) = match (self.positive, self.negative) {
            (Some((m, s)), Some((_, o))) => (m, s, o),
            (Some((m, s)), None) | (None, Some((m, s))) => (m, s, zero),
            (None, None) => unreachable!("a group holds at least one row"),
        };
        PairedRows {
            m,
            plus: same.iter().zip(&opposite).map(|(a, b)| a + b).collect(),
            minus: same.iter().zip(&opposite).map(|(a, b)| a - b).collect(),
        }
    }
}

/// Concatenates per-depth component arrays of `n` values each.
fn gather(per_depth: Vec<Components>, n: usize) -> Components {
    let mut out: Components = std::array::from_fn(|_| Vec::with_capacity(n * per_depth.len()));
    for depth in per_depth {
        for (o, d) in out.iter_mut().zip(depth) {
            o.extend_from_slice(&d);
        }
    }
    out
}
