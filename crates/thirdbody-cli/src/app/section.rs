//! Which stress section a result is, as the CLI shows it: the library's
//! [`SectionId`] (the identity of each computed section) with the CLI's labels. File
//! names come from [`SectionId::name`]; this module adds the plot legends and the
//! look-ups the outputs need.

use anyhow::Result;
use thirdbody::stress::{Side, StressField, StressResults};

pub use thirdbody::stress::SectionId;

/// Labels of a section in the CLI's plots.
pub trait SectionLabels {
    /// Legend label of its sigma_x row in `stress_sigma_x.png` (paper Figs. 9 and
    /// 12): the surface and both sides of each interface have one, other sections
    /// none.
    fn sigma_x_row_label(self) -> Option<String>;
}

impl SectionLabels for SectionId {
    fn sigma_x_row_label(self) -> Option<String> {
        match self {
            SectionId::Surface => Some("surface".into()),
            SectionId::Interface { index, side } => Some(format!(
                "interface {index}, {} side",
                match side {
                    Side::Above => "upper",
                    Side::Below => "lower",
                }
            )),
            _ => None,
        }
    }
}

/// Each section of `results` with its identity.
pub fn sections(results: &StressResults) -> Result<Vec<(SectionId, &StressField)>> {
    Ok(results
        .sections
        .iter()
        .map(|(named, f)| (named.id, f))
        .collect())
}

/// The section `id` of `results`, if it was computed.
pub fn find(results: &StressResults, id: SectionId) -> Option<&StressField> {
    results
        .sections
        .iter()
        .find(|(named, _)| named.id == id)
        .map(|(_, f)| f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_surface_and_the_interface_have_sigma_x_rows() {
        let labelled: Vec<SectionId> = [
            SectionId::Xz,
            SectionId::Surface,
            SectionId::Interface {
                index: 0,
                side: Side::Above,
            },
            SectionId::Interface {
                index: 1,
                side: Side::Below,
            },
            SectionId::Block,
            SectionId::Plane(2),
        ]
        .into_iter()
        .filter(|id| id.sigma_x_row_label().is_some())
        .collect();
        assert_eq!(
            labelled,
            [
                SectionId::Surface,
                SectionId::Interface {
                    index: 0,
                    side: Side::Above,
                },
                SectionId::Interface {
                    index: 1,
                    side: Side::Below,
                },
            ]
        );
    }
}
