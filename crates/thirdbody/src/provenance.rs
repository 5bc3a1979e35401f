//! Where a result comes from: the thirdbody version, the git commit the library was
//! built from (when it was built from a git checkout), a hash that identifies the
//! case, and the published work the computation relies on, as BibTeX (`thirdbody
//! cite`). Every `summary.json` and `results.csv` row carries the first three.

use sha2::{Digest, Sha256};

use crate::case::Case;

/// The library's version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The git commit the library was built from, when known.
pub fn commit() -> Option<&'static str> {
    option_env!("THIRDBODY_GIT_COMMIT")
}

/// SHA-256 (hex) of the case's canonical text: its parsed form written out in full
/// (every field, defaults included, numbers in their shortest round-trip form), so
/// two case files that differ only in layout, comments, key order or spelled-out
/// defaults have the same hash. The text is the library's debug form of [`Case`],
/// so the hash identifies a case within one thirdbody version, not across versions
/// that rename fields.
pub fn case_hash(case: &Case) -> String {
    let canonical = format!("{case:?}");
    let digest = Sha256::digest(canonical.as_bytes());
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// The works the computation relies on, as BibTeX.
pub const REFERENCES: &str = r#"@article{torskaya2023nonlinear,
  author  = {Torskaya, Elena V. and Stepanov, Fedor I.},
  title   = {Effect of Non-Linear Properties of Intermediate Layer on Sliding Contact of Homogeneous and Coated Elastic Solids},
  journal = {Lubricants},
  volume  = {11},
  number  = {8},
  pages   = {333},
  year    = {2023},
  doi     = {10.3390/lubricants11080333}
}

@article{love1929stress,
  author  = {Love, A. E. H.},
  title   = {The stress produced in a semi-infinite solid by pressure on part of the boundary},
  journal = {Philosophical Transactions of the Royal Society of London. Series A},
  volume  = {228},
  pages   = {377--420},
  year    = {1929}
}

@article{liu2000dcfft,
  author  = {Liu, Shuangbiao and Wang, Qian and Liu, Geng},
  title   = {A versatile method of discrete convolution and {FFT} ({DC-FFT}) for contact analyses},
  journal = {Wear},
  volume  = {243},
  pages   = {101--111},
  year    = {2000}
}

@article{polonsky1999numerical,
  author  = {Polonsky, I. A. and Keer, L. M.},
  title   = {A numerical method for solving rough contact problems based on the multi-level multi-summation and conjugate gradient techniques},
  journal = {Wear},
  volume  = {231},
  pages   = {206--219},
  year    = {1999}
}

@article{chen1971layered,
  author  = {Chen, W. T.},
  title   = {Computation of stresses and displacements in a layered elastic medium},
  journal = {International Journal of Engineering Science},
  volume  = {9},
  pages   = {775--800},
  year    = {1971}
}

@article{osullivan1988sliding,
  author  = {O'Sullivan, T. C. and King, R. B.},
  title   = {Sliding contact stress field due to a spherical indenter on a layered elastic half-space},
  journal = {Journal of Tribology},
  volume  = {110},
  pages   = {235--240},
  year    = {1988}
}

@article{perriot2004elastic,
  author  = {Perriot, A. and Barthel, E.},
  title   = {Elastic contact to a coated half-space: effective elastic modulus and real penetration},
  journal = {Journal of Materials Research},
  volume  = {19},
  pages   = {600--608},
  year    = {2004}
}
"#;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case_file::parse_case_file;

    fn parse(text: &str) -> Case {
        let mut no_maps =
            |_: &str, _: f64| -> crate::Result<crate::HeightMap> { unreachable!("no height map") };
        parse_case_file(text, &mut no_maps).unwrap().case
    }

    const CASE: &str = "[slider]\nshape = \"sphere\"\nradius = 1.0\n[substrate]\nyoung = 1.0\npoisson = 0.3\n[loading]\nnormal_load = 5e-6\n[grid]\ncells = [32, 32]\n";

    #[test]
    fn the_case_hash_ignores_layout_and_sees_every_value() {
        let a = case_hash(&parse(CASE));
        // Layout, comments and number spelling do not change the case.
        let relaid = CASE
            .replace("radius = 1.0", "# a comment\nradius   = 1")
            .replace("5e-6", "0.000005");
        assert_eq!(case_hash(&parse(&relaid)), a);
        // A value does.
        let other = CASE.replace("5e-6", "5.000000000001e-6");
        assert_ne!(case_hash(&parse(&other)), a);
        assert_eq!(a.len(), 64);
        assert!(a.bytes().all(|b| b.is_ascii_hexdigit()));
    }

    #[test]
    fn the_references_are_bibtex_entries_with_distinct_keys() {
        let keys: Vec<&str> = REFERENCES
            .lines()
            .filter_map(|l| l.strip_prefix('@'))
            .map(|l| l.split_once('{').unwrap().1.trim_end_matches(','))
            .collect();
        assert_eq!(keys.len(), 7);
        let mut sorted = keys.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), keys.len());
        assert_eq!(
            REFERENCES.matches('{').count(),
            REFERENCES.matches('}').count()
        );
    }

    #[test]
    fn the_commit_is_a_full_hash_when_known() {
        if let Some(c) = commit() {
            assert_eq!(c.len(), 40);
        }
        assert!(!VERSION.is_empty());
    }
}
