//! The caller-owned store of what is costly to build and reusable between solves:
//! DC-FFT plans (one per grid size and parallelism) and surface kernels (one per
//! body, grid size and cell size; a coated kernel costs 0.1-6 s at 256²), held as
//! their quadrant: the operator that uses one builds its spectrum on the padding
//! its products need. Like
//! rustfft's `FftPlanner`, it is an ordinary value: the CLI's `solve` makes one, each
//! sweep worker has its own, a Python `Solver` would own one. Nothing is global, two
//! caches never share data, and the caller sizes it ([`KernelCache::with_capacity`])
//! and empties it ([`KernelCache::clear`]). Cached spectra are bitwise those built
//! afresh.

use std::sync::Arc;

use crate::body::surface_kernel;
use crate::case::Body;
use crate::convolution::{ConvolutionPlan, KernelSpectrum, Parallelism};
use crate::error::Result;
use crate::grid::{Geometry, Grid};

/// Spectra kept by default: the windows an automatic solve tries for a few bodies.
const DEFAULT_CAPACITY: usize = 8;
/// Bytes of kernels kept at most: a surface kernel's quadrant takes 8 bytes per
/// cell (a 1024² grid's 8 MB), so large grids keep fewer; one larger than this is
/// not kept.
const DEFAULT_BYTE_BUDGET: usize = 256 << 20;

/// What a surface-kernel spectrum depends on: the body, the grid size, the cell
/// size (bitwise) and, for a body whose kernel depends on it, the sliding speed
/// (bitwise).
#[derive(Debug, Clone, PartialEq)]
struct SpectrumKey {
    body: Body,
    cells: [usize; 2],
    cell_bits: u64,
    geometry: Geometry,
    velocity_bits: Option<u64>,
    lag: bool,
}

/// What a DC-FFT plan depends on: the grid size and the parallelism.
type PlanKey = ([usize; 2], Parallelism);

/// Plans and kernel spectra kept between solves, least recently used dropped first.
#[derive(Debug)]
pub struct KernelCache {
    capacity: usize,
    byte_budget: usize,
    plans: Vec<(PlanKey, Arc<ConvolutionPlan>)>,
    spectra: Vec<(SpectrumKey, Arc<KernelSpectrum>)>,
    /// Surface kernels built because none was held.
    spectra_built: usize,
    /// Surface kernels found held.
    spectra_reused: usize,
}

impl Default for KernelCache {
    fn default() -> Self {
        KernelCache::with_capacity(DEFAULT_CAPACITY)
    }
}

impl KernelCache {
    /// An empty cache that keeps up to 8 spectra and 8 plans.
    pub fn new() -> Self {
        KernelCache::default()
    }

    /// An empty cache that keeps up to `capacity` spectra (and at most 256 MiB of
    /// them) and as many plans (0 keeps nothing: every solve builds its own).
    pub fn with_capacity(capacity: usize) -> Self {
        KernelCache {
            capacity,
            byte_budget: DEFAULT_BYTE_BUDGET,
            plans: Vec::new(),
            spectra: Vec::new(),
            spectra_built: 0,
            spectra_reused: 0,
        }
    }

    /// Spectra held now.
    pub fn len(&self) -> usize {
        self.spectra.len()
    }

    /// Whether no spectrum is held.
    pub fn is_empty(&self) -> bool {
        self.spectra.is_empty()
    }

    /// Surface kernels this cache has built (none was held for the body, grid size and
    /// cell size asked for) since it was made: what a caller reusing it saves.
    pub fn spectra_built(&self) -> usize {
        self.spectra_built
    }

    /// Surface kernels this cache has handed out without building them.
    pub fn spectra_reused(&self) -> usize {
        self.spectra_reused
    }

    /// Drops every plan and spectrum (the counts of built and reused kernels stay).
    pub fn clear(&mut self) {
        self.plans.clear();
        self.spectra.clear();
    }

    /// The DC-FFT plan for fields of `nx x ny` cells; a grid without cells is an
    /// error ([`ConvolutionPlan::new`]).
    pub fn plan(
        &mut self,
        nx: usize,
        ny: usize,
        parallelism: Parallelism,
    ) -> Result<Arc<ConvolutionPlan>> {
        let key: PlanKey = ([nx, ny], parallelism);
        if let Some(k) = self.plans.iter().position(|(k, _)| *k == key) {
            let entry = self.plans.remove(k);
            let plan = Arc::clone(&entry.1);
            self.plans.push(entry);
            return Ok(plan);
        }
        let plan = ConvolutionPlan::new(nx, ny, parallelism)?;
        keep(&mut self.plans, (key, Arc::clone(&plan)), self.capacity);
        Ok(plan)
    }

    /// The surface kernel of `body` on `grid`'s cells at sliding speed `velocity`,
    /// for `plan` (which must be for `grid`'s size), unless held: an even kernel
    /// given by its quadrant, with no spectrum built
    /// ([`crate::convolution::ConvolutionPlan::even_kernel`]). `lag` as for
    /// [`crate::body::BodyModel::surface_kernel`].
    pub fn surface_spectrum(
        &mut self,
        body: &Body,
        grid: &Grid,
        plan: &Arc<ConvolutionPlan>,
        velocity: f64,
        lag: bool,
    ) -> Result<Arc<KernelSpectrum>> {
        let model = body.model();
        // With no lag to leave out, both kernels are the same: one key for them.
        let lag = lag && model.creep_shift(grid.cell, velocity) != 0.0;
        let key = SpectrumKey {
            body: body.clone(),
            cells: [grid.nx, grid.ny],
            cell_bits: grid.cell.to_bits(),
            geometry: grid.geometry(),
            velocity_bits: model
                .kernel_depends_on_velocity()
                .then_some(velocity.to_bits()),
            lag,
        };
        if let Some(k) = self.spectra.iter().position(|(k, _)| *k == key) {
            let entry = self.spectra.remove(k);
            let spectrum = Arc::clone(&entry.1);
            self.spectra.push(entry);
            self.spectra_reused += 1;
            return Ok(spectrum);
        }
        let spectrum = Arc::new(surface_kernel(body, grid, plan, velocity, lag)?);
        self.spectra_built += 1;
        if spectrum.bytes() <= self.byte_budget {
            keep(
                &mut self.spectra,
                (key, Arc::clone(&spectrum)),
                self.capacity,
            );
            while self.spectra.iter().map(|(_, s)| s.bytes()).sum::<usize>() > self.byte_budget {
                self.spectra.remove(0);
            }
        }
        Ok(spectrum)
    }
}

/// Appends `entry` as the most recently used, dropping the oldest beyond `capacity`.
fn keep<T>(entries: &mut Vec<T>, entry: T, capacity: usize) {
    if capacity == 0 {
        return;
    }
    if entries.len() >= capacity {
        entries.remove(0);
    }
    entries.push(entry);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::Elastic;

    fn coated(thickness: f64) -> Body {
        Body::coated(
            Elastic {
                young: 3.0,
                poisson: 0.3,
            },
            thickness,
            Elastic {
                young: 1.0,
                poisson: 0.3,
            },
        )
    }

    #[test]
    fn a_held_spectrum_is_shared_and_equals_a_fresh_one() {
        let grid = Grid::centred(16, 12, 0.5, [0.0, 0.0]).unwrap();
        let mut cache = KernelCache::new();
        let plan = cache.plan(16, 12, Parallelism::Sequential).unwrap();
        let first = cache
            .surface_spectrum(&coated(0.37), &grid, &plan, 1.0, true)
            .unwrap();
        let again = cache
            .surface_spectrum(&coated(0.37), &grid, &plan, 1.0, true)
            .unwrap();
        assert!(Arc::ptr_eq(&first, &again));
        let other = cache
            .surface_spectrum(&coated(0.38), &grid, &plan, 1.0, true)
            .unwrap();
        assert!(!Arc::ptr_eq(&first, &other));
        assert_eq!(cache.len(), 2);
        let fresh = surface_kernel(&coated(0.37), &grid, &plan, 1.0, true).unwrap();
        assert_eq!(format!("{fresh:?}"), format!("{first:?}"));
        // A bad body is an error, and nothing is kept for it.
        assert!(cache
            .surface_spectrum(&coated(-1.0), &grid, &plan, 1.0, true)
            .is_err());
        assert_eq!(cache.len(), 2);
        // Two built, one handed out again; the failed one is not counted.
        assert_eq!((cache.spectra_built(), cache.spectra_reused()), (2, 1));
    }

    #[test]
    fn capacity_bounds_what_is_held_and_clear_empties_it() {
        let grid = Grid::centred(8, 8, 0.5, [0.0, 0.0]).unwrap();
        let mut cache = KernelCache::with_capacity(2);
        let plan = cache.plan(8, 8, Parallelism::Sequential).unwrap();
        for t in [0.1, 0.2, 0.3] {
            cache
                .surface_spectrum(&coated(t), &grid, &plan, 1.0, true)
                .unwrap();
        }
        assert_eq!(cache.len(), 2);
        cache.clear();
        assert!(cache.is_empty());
        let mut none = KernelCache::with_capacity(0);
        none.surface_spectrum(&coated(0.1), &grid, &plan, 1.0, true)
            .unwrap();
        assert!(none.is_empty());
    }
}
