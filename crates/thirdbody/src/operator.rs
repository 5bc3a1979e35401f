//! The elastic influence operator seen by the contact solvers: `w = K p`, the
//! normal surface displacement of the body for a cell-wise constant pressure
//! (paper eq. 7's `A^(1)` part). Solvers take anything that applies `K` so that tests
//! can drive them with a small dense matrix (style: argmin's problem trait, faer's
//! `LinOp`); production uses the DC-FFT convolution.

use std::sync::Arc;

use crate::convolution::{Convolver, KernelSpectrum};

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
    /// `w = K p`.
    fn apply(&mut self, p: &[f64], w: &mut [f64]);
    /// Products `K p` computed so far (for cost accounting; 0 if not counted).
    fn products(&self) -> usize {
        0
    }
}

/// `K` applied by DC-FFT with a cached kernel spectrum.
pub struct ConvolutionOperator {
    convolver: Convolver,
    kernel: Arc<KernelSpectrum>,
    products: usize,
}

impl ConvolutionOperator {
    /// Pairs a scratch with a kernel spectrum built on the same plan.
    pub fn new(convolver: Convolver, kernel: Arc<KernelSpectrum>) -> Self {
        ConvolutionOperator {
            convolver,
            kernel,
            products: 0,
        }
    }
}

impl InfluenceOperator for ConvolutionOperator {
    fn len(&self) -> usize {
        self.convolver.plan().nx() * self.convolver.plan().ny()
    }
    fn self_coefficient(&self) -> f64 {
        self.kernel.self_coefficient()
    }
    fn apply(&mut self, p: &[f64], w: &mut [f64]) {
        self.convolver.apply(&self.kernel, p, w);
        self.products += 1;
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
        DenseOperator { n, values }
    }

    /// Entry `(i, j)`.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.values[i * self.n + j]
    }
}

impl InfluenceOperator for DenseOperator {
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
}
