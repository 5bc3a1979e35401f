//! Which stress section a result is, as the CLI sees it. The library names its
//! sections (`thirdbody::stress::NamedSection::name`: `xz`, `surface`,
//! `interface_coating`, `interface_substrate`, `block`, `plane_1`, ...); this module is
//! the only place the CLI reads that name: [`SectionId::of`] parses it once, and the
//! file names and legend labels are methods. When the library carries the identity as
//! an enum, only this module changes.

use std::borrow::Cow;

use anyhow::{anyhow, Result};
use thirdbody::stress::{NamedSection, StressField, StressResults};

/// A section's identity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SectionId {
    /// The XZ plane y = const.
    Xz,
    /// The surface z = 0.
    Surface,
    /// The coating side of a coated body's interface.
    InterfaceCoating,
    /// The substrate side of a coated body's interface.
    InterfaceSubstrate,
    /// The 3-D block.
    Block,
    /// A further plane z = const (`planes` of the request), numbered from 1.
    Plane(usize),
}

impl SectionId {
    /// Parses a section name of the library.
    pub fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "xz" => SectionId::Xz,
            "surface" => SectionId::Surface,
            "interface_coating" => SectionId::InterfaceCoating,
            "interface_substrate" => SectionId::InterfaceSubstrate,
            "block" => SectionId::Block,
            _ => SectionId::Plane(name.strip_prefix("plane_")?.parse().ok()?),
        })
    }

    /// The identity of a computed section.
    pub fn of(named: &NamedSection) -> Result<Self> {
        Self::parse(&named.name)
            .ok_or_else(|| anyhow!("unknown stress section {:?} (a newer library?)", named.name))
    }

    /// The section's name in file names (`stress_<name>.npy`) and in `summary.json`.
    pub fn name(self) -> Cow<'static, str> {
        Cow::Borrowed(match self {
            SectionId::Xz => "xz",
            SectionId::Surface => "surface",
            SectionId::InterfaceCoating => "interface_coating",
            SectionId::InterfaceSubstrate => "interface_substrate",
            SectionId::Block => "block",
            SectionId::Plane(k) => return Cow::Owned(format!("plane_{k}")),
        })
    }

    /// Legend label of its sigma_x row in `stress_sigma_x.png` (paper Figs. 9 and 12):
    /// the surface and both sides of the interface have one, other sections none.
    pub fn sigma_x_row_label(self) -> Option<&'static str> {
        match self {
            SectionId::Surface => Some("surface"),
            SectionId::InterfaceCoating => Some("interface, coating side"),
            SectionId::InterfaceSubstrate => Some("interface, substrate side"),
            _ => None,
        }
    }
}

/// Each section of `results` with its identity.
pub fn sections(results: &StressResults) -> Result<Vec<(SectionId, &StressField)>> {
    results
        .sections
        .iter()
        .map(|(named, f)| Ok((SectionId::of(named)?, f)))
        .collect()
}

/// The section `id` of `results`, if it was computed.
pub fn find(results: &StressResults, id: SectionId) -> Option<&StressField> {
    results
        .sections
        .iter()
        .find(|(named, _)| SectionId::of(named).ok() == Some(id))
        .map(|(_, f)| f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for id in [
            SectionId::Xz,
            SectionId::Surface,
            SectionId::InterfaceCoating,
            SectionId::InterfaceSubstrate,
            SectionId::Block,
            SectionId::Plane(12),
        ] {
            assert_eq!(SectionId::parse(&id.name()), Some(id));
        }
        for name in ["interface", "plane_", "plane_x", "XZ"] {
            assert_eq!(SectionId::parse(name), None, "{name}");
        }
    }
}
