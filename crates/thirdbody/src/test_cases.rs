//! Case files the unit tests share: one text per kind of case, so that a change
//! of the case-file format is made once.

/// Hertz's case: a sphere (R = 1) pressed with a load of 5e-6 on a homogeneous
/// half-space (E = 1, nu = 0.3), no layer, on a 32 x 32 automatic window.
pub(crate) const HERTZ: &str = "[slider]\nshape = \"sphere\"\nradius = 1.0\n[substrate]\n\
                                young = 1.0\npoisson = 0.3\n[loading]\nnormal_load = 5e-6\n\
                                [grid]\ncells = [32, 32]\n";

/// The paper's layer (Maxwell, C' = 0.02, T = 1, linear law) under Hertz's sphere
/// and load at V' = 1e-3, on a 32 x 32 automatic window.
pub(crate) const MAXWELL_LAYER: &str = "[slider]\nshape = \"sphere\"\nradius = 1.0\n\
                                        [substrate]\nyoung = 1.0\npoisson = 0.3\n[layer]\n\
                                        compliance = 0.02\nrelaxation_time = 1.0\n\
                                        [loading]\nnormal_load = 5e-6\nvelocity = 1e-3\n\
                                        [grid]\ncells = [32, 32]\n";

/// A case file's case, for a text that reads no height map.
pub(crate) fn parse(text: &str) -> crate::Case {
    crate::case_file::parse_case_file(text, &mut |_, _| unreachable!("no height map"))
        .unwrap()
        .case
}
