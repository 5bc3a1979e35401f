//! Vector passes of the iterative solvers split over threads with results that do
//! not depend on the thread count: a field is cut into fixed chunks of [`CHUNK`]
//! cells, each chunk's partial sums are formed in a fixed order (cell order, or
//! [`LANES`] interleaved running sums added in order, [`lane_sum`]), and the partials
//! are added in chunk order. One thread or many give the same bits, so a solve's
//! iterates and iteration count are identical with 1 and N threads.

use rayon::prelude::*;

use crate::convolution::{Parallelism, PARALLEL_MIN_CELLS};

/// Cells per chunk: large enough that a chunk's work hides the hand-off, small
/// enough to share 2-64 threads on the grids worth splitting (128² and up).
pub(crate) const CHUNK: usize = 4096;

/// How the passes over one grid are run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Passes {
    /// Smallest number of chunks rayon may hand to one task (`usize::MAX`: none are
    /// split off, the pass runs on the calling thread).
    min_chunks: usize,
}

impl Passes {
    /// Passes over fields of `cells` cells: split over the rayon pool when asked for
    /// and the grid has at least [`PARALLEL_MIN_CELLS`] cells.
    pub(crate) fn new(cells: usize, parallelism: Parallelism) -> Self {
        let parallel = parallelism == Parallelism::Rayon
            && cells >= PARALLEL_MIN_CELLS
            && rayon::current_num_threads() > 1;
        Passes {
            min_chunks: if parallel { 1 } else { usize::MAX },
        }
    }

    /// The value for rayon's `with_min_len` on a chunked iterator.
    pub(crate) fn min_len(&self) -> usize {
        self.min_chunks
    }

    /// The value for rayon's `with_min_len` on an iterator over single cells (or
    /// contact-set entries): a chunk's worth per task.
    pub(crate) fn min_cells(&self) -> usize {
        if self.min_chunks == 1 {
            CHUNK
        } else {
            usize::MAX
        }
    }

    /// `x *= factor`, cell by cell.
    pub(crate) fn scale(&self, x: &mut [f64], factor: f64) {
        x.par_chunks_mut(CHUNK)
            .with_min_len(self.min_chunks)
            .for_each(|c| c.iter_mut().for_each(|v| *v *= factor));
    }

    /// The value for rayon's `with_min_len` on an iterator over rows of `nx` cells:
    /// about a chunk's worth of rows per task.
    pub(crate) fn min_rows(&self, nx: usize) -> usize {
        if self.min_chunks == 1 {
            CHUNK.div_ceil(nx.max(1))
        } else {
            usize::MAX
        }
    }

    /// Runs `partial` on every chunk's cell range `start..end`; the results in chunk
    /// order.
    pub(crate) fn partials<T: Send>(
        &self,
        cells: usize,
        partial: impl Fn(usize, usize) -> T + Sync,
    ) -> Vec<T> {
        let chunks = cells.div_ceil(CHUNK);
        (0..chunks)
            .into_par_iter()
            .with_min_len(self.min_chunks)
            .map(|c| partial(c * CHUNK, ((c + 1) * CHUNK).min(cells)))
            .collect()
    }

    /// Runs `partial` on every chunk's cell range `start..end` and adds the partial
    /// sums in chunk order (component-wise).
    pub(crate) fn sum<const K: usize>(
        &self,
        cells: usize,
        partial: impl Fn(usize, usize) -> [f64; K] + Sync,
    ) -> [f64; K] {
        add_in_order(&self.partials(cells, partial))
    }
}

/// Running sums a chunk's cells are dealt to in turn (cell `k` of a chunk to sum
/// `k % LANES`), added in order at the chunk's end. One running sum would make
/// every addition wait for the one before (about 4 cycles a cell); independent ones
/// overlap, and the order is still fixed.
pub(crate) const LANES: usize = 8;

/// The sums of `term(k)` (component-wise) over the cells `a..b` of one chunk, in
/// [`LANES`] interleaved running sums added in order.
#[inline(always)]
pub(crate) fn lane_sum<const K: usize>(
    a: usize,
    b: usize,
    mut term: impl FnMut(usize) -> [f64; K],
) -> [f64; K] {
    let mut lanes = [[0.0; K]; LANES];
    let mut k = a;
    while k + LANES <= b {
        for (l, lane) in lanes.iter_mut().enumerate() {
            let t = term(k + l);
            for (s, v) in lane.iter_mut().zip(t) {
                *s += v;
            }
        }
        k += LANES;
    }
    for (lane, k) in lanes.iter_mut().zip(k..b) {
        let t = term(k);
        for (s, v) in lane.iter_mut().zip(t) {
            *s += v;
        }
    }
    add_in_order(&lanes)
}

/// [`lane_sum`] of the first part of `term(k)`, and the largest of its second part.
#[inline(always)]
pub(crate) fn lane_sum_max<const K: usize>(
    a: usize,
    b: usize,
    mut term: impl FnMut(usize) -> ([f64; K], f64),
) -> ([f64; K], f64) {
    let mut largest = [f64::NEG_INFINITY; LANES];
    let sums = lane_sum(a, b, |k| {
        let (t, m) = term(k);
        let lane = &mut largest[(k - a) % LANES];
        *lane = lane.max(m);
        t
    });
    (sums, largest.into_iter().fold(f64::NEG_INFINITY, f64::max))
}

/// The component-wise sum of chunk partials, in their order.
pub(crate) fn add_in_order<const K: usize>(partials: &[[f64; K]]) -> [f64; K] {
    let mut total = [0.0; K];
    for part in partials {
        for (t, v) in total.iter_mut().zip(part) {
            *t += v;
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_are_the_same_bits_on_one_thread_and_on_four() {
        let n = 200_003;
        let x: Vec<f64> = (0..n)
            .map(|k| ((k * 7919) % 1000) as f64 * 1e-3 + 1e-9)
            .collect();
        let pass = |range_start: usize, end: usize| -> [f64; 2] {
            let s: f64 = x[range_start..end].iter().sum();
            let q: f64 = x[range_start..end].iter().map(|v| v * v).sum();
            [s, q]
        };
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let four = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        let a = one.install(|| Passes::new(n, Parallelism::Rayon).sum(n, pass));
        let b = four.install(|| Passes::new(n, Parallelism::Rayon).sum(n, pass));
        let c = Passes::new(n, Parallelism::Sequential).sum(n, pass);
        assert_eq!(a, b);
        assert_eq!(a, c);
        // Against a plain sum (a second method): equal to rounding.
        let plain: f64 = x.iter().sum();
        assert!((a[0] - plain).abs() < 1e-12 * plain);
    }

    #[test]
    fn lane_sums_equal_a_plain_sum_to_rounding_and_cover_every_cell() {
        let x: Vec<f64> = (0..1003).map(|k| ((k * 31) % 17) as f64 - 8.0).collect();
        for (a, b) in [(0, 1003), (5, 13), (0, 7), (3, 3), (8, 1000)] {
            let [s, count] = lane_sum(a, b, |k| [x[k], 1.0]);
            // Integers: every order gives the exact sum.
            assert_eq!(s, x[a..b].iter().sum::<f64>());
            assert_eq!(count, (b - a) as f64);
        }
    }
}
