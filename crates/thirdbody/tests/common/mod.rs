//! Test-only helpers shared by the integration tests.

pub mod rigid_base;
pub mod rigid_base_burgers;
pub mod rigid_base_viscoelastic;
