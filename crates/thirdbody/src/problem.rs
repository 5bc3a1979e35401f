//! The assembly stage (docs/architecture.md): a [`Case`] (plain data) and a window
//! become the numerical contact problem the solvers see, [`ContactProblem`]: the
//! body's influence operator `K` (a DC-FFT convolution with the body's kernel
//! spectrum), the layer's response `w3(p)` (any rheology, through
//! [`LayerResponse`]), the slider's height f and slope df/dx at the cell centres, and
//! the load Q. The conditions it poses are the paper's eq. 3-4 and system (6) as
//! docs/architecture.md (conventions) states them: `K p + w3(p) + f - D = 0` where
//! p > 0, the gap >= 0 where p = 0, and `sum(p) h^2 = Q`. The solvers hold only their iteration state; nothing in them
//! knows which body or rheology the problem came from.

use std::sync::Arc;

use crate::case::{Body, Case};
use crate::contact::window::ContactEstimate;
use crate::convolution::Parallelism;
use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::kernel_cache::KernelCache;
use crate::layer::LayerResponse;
use crate::operator::{ConvolutionOperator, InfluenceOperator};

/// One contact problem on one window, ready for a solver.
pub struct ContactProblem {
    pub(crate) grid: Grid,
    /// The case's body, for the solution (stresses) and the dense reference.
    pub(crate) body: Body,
    pub(crate) influence: Box<dyn InfluenceOperator + Send>,
    pub(crate) layer: Option<Box<dyn LayerResponse>>,
    pub(crate) shape: Vec<f64>,
    pub(crate) slope: Vec<f64>,
    pub(crate) load: f64,
    /// The sliding speed (a viscoelastic body's kernel and dissipation use it).
    pub(crate) velocity: f64,
    /// The constant the body's kernel was lowered by (a line contact's datum,
    /// [`crate::convolution::KernelSpectrum::datum_shift`]): the solution adds it
    /// times the sum of the cells' pressures to the body's displacement and the
    /// approach.
    pub(crate) datum_shift: f64,
    /// The lag `c` of a viscoelastic body's creep shorter than a cell
    /// ([`crate::body::BodyModel::creep_shift`]): `shape` holds the slider's height
    /// read at `f - c df/dx`, and the solution gives the lag back to the body's
    /// displacement.
    pub(crate) creep_shift: f64,
    pub(crate) estimate: ContactEstimate,
}

impl std::fmt::Debug for ContactProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ContactProblem")
            .field("grid", &self.grid)
            .field("body", &self.body)
            .field("layer", &self.layer)
            .field("load", &self.load)
            .finish_non_exhaustive()
    }
}

impl Case {
    /// Builds the contact problem of this case on `grid`, taking the FFT plan and the
    /// body's kernel spectrum from `kernels` (built there if not held).
    pub fn assemble(
        &self,
        grid: &Grid,
        kernels: &mut KernelCache,
        parallelism: Parallelism,
    ) -> Result<ContactProblem> {
        let plan = kernels.plan(grid.nx, grid.ny, parallelism)?;
        let velocity = self.velocity();
        // Without a layer the slider's shape is the body's displacement on the
        // contact, so a body may give a lag of it to the gap.
        let lag = self.layer.is_none();
        let spectrum = kernels.surface_spectrum(&self.body, grid, &plan, velocity, lag)?;
        let datum_shift = spectrum.datum_shift();
        let influence = ConvolutionOperator::new(plan.convolver(), Arc::clone(&spectrum))?;
        let n = grid.len();
        let mut shape = vec![0.0; n];
        let mut slope = vec![0.0; n];
        self.slider
            .sample_rows(grid, &mut shape, &mut slope, parallelism)?;
        let creep_shift = if lag {
            self.body.model().creep_shift(grid.cell, velocity)
        } else {
            0.0
        };
        if creep_shift != 0.0 {
            shape
                .iter_mut()
                .zip(&slope)
                .for_each(|(f, d)| *f -= creep_shift * d);
        }
        Ok(ContactProblem {
            grid: *grid,
            body: self.body.clone(),
            influence: Box::new(influence),
            layer: self
                .layer
                .as_ref()
                .map(|l| l.on_grid(grid, velocity, parallelism)),
            shape,
            slope,
            load: self.loading.normal_load,
            velocity,
            datum_shift,
            creep_shift,
            estimate: ContactEstimate::of(self),
        })
    }
}

impl ContactProblem {
    /// A problem from its parts, for driving the solvers with other operators (a
    /// dense matrix in tests). `shape` and `slope` are f and df/dx per cell. An
    /// operator, `shape` or `slope` whose size is not the grid's number of cells is an
    /// [`Error::InvalidValue`] naming the argument.
    pub fn from_parts(
        case: &Case,
        grid: &Grid,
        influence: Box<dyn InfluenceOperator + Send>,
        shape: Vec<f64>,
        slope: Vec<f64>,
    ) -> Result<Self> {
        let cells = grid.len();
        for (name, len) in [
            ("influence operator size", influence.len()),
            ("shape length", shape.len()),
            ("slope length", slope.len()),
        ] {
            if len != cells {
                let allowed = format!("the grid's {} x {} = {cells} cells", grid.nx, grid.ny);
                return Err(Error::invalid(name, len, &allowed));
            }
        }
        Ok(ContactProblem {
            grid: *grid,
            body: case.body.clone(),
            influence,
            layer: case
                .layer
                .as_ref()
                .map(|l| l.on_grid(grid, case.velocity(), Parallelism::Rayon)),
            shape,
            slope,
            load: case.loading.normal_load,
            velocity: case.velocity(),
            datum_shift: 0.0,
            creep_shift: 0.0,
            estimate: ContactEstimate::of(case),
        })
    }

    /// Whether the body's kernel left a lag of its displacement to the gap
    /// ([`crate::body::BodyModel::creep_shift`]; assembled without a layer, a
    /// viscoelastic body creeping over less than a few cells). Where it did not,
    /// the kernels with and without the lag are the same.
    pub fn body_lag(&self) -> bool {
        self.creep_shift != 0.0
    }

    /// The window and cells.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The slider's height f at the cell centres.
    pub fn shape(&self) -> &[f64] {
        &self.shape
    }

    /// The slider's slope `df/dx` at the cell centres (the layer's friction).
    pub fn slope(&self) -> &[f64] {
        &self.slope
    }

    /// The case's body.
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// The sliding speed V (a viscoelastic body's kernel and dissipation use it).
    pub fn velocity(&self) -> f64 {
        self.velocity
    }

    /// The normal load Q.
    pub fn load(&self) -> f64 {
        self.load
    }

    /// The layer's response, if there is a layer.
    pub fn layer(&self) -> Option<&dyn LayerResponse> {
        self.layer.as_deref()
    }

    /// `Some(c_w)` when the operator is symmetric positive definite (`K + c_w I`
    /// with a symmetric body operator `K`, [`InfluenceOperator::is_symmetric`], and
    /// no layer, c_w = 0, or a creep-free linear layer): conjugate gradients apply.
    pub fn winkler_compliance(&self) -> Option<f64> {
        if !self.influence.is_symmetric() {
            return None;
        }
        match &self.layer {
            None => Some(0.0),
            Some(l) => l.winkler_compliance(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operator::DenseOperator;

    #[test]
    fn parts_of_the_wrong_size_are_an_input_error_naming_the_argument() {
        let case = crate::test_cases::parse(crate::test_cases::HERTZ);
        let grid = Grid::centred(8, 8, 0.01, [0.0, 0.0]).unwrap();
        let parts = |n_operator: usize, n_shape: usize, n_slope: usize| {
            ContactProblem::from_parts(
                &case,
                &grid,
                Box::new(DenseOperator::from_fn(n_operator, |i, j| {
                    f64::from(u8::from(i == j))
                })),
                vec![0.0; n_shape],
                vec![0.0; n_slope],
            )
        };
        assert!(parts(64, 64, 64).is_ok());
        for (sizes, message) in [
            (
                (63, 64, 64),
                "influence operator size = 63 is not allowed: the grid's 8 x 8 = 64 cells",
            ),
            (
                (64, 65, 64),
                "shape length = 65 is not allowed: the grid's 8 x 8 = 64 cells",
            ),
            (
                (64, 64, 0),
                "slope length = 0 is not allowed: the grid's 8 x 8 = 64 cells",
            ),
        ] {
            let e = parts(sizes.0, sizes.1, sizes.2).unwrap_err();
            assert!(e.is_input());
            assert_eq!(e.to_string(), message);
        }
    }
}
