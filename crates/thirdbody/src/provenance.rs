//! Where a result comes from: the thirdbody version, the git commit the library was
//! built from (when it was built from a git checkout), a hash that identifies the
//! case, and the published work the computation relies on: all of it as BibTeX
//! ([`REFERENCES`]), and the works one case uses with what each is used for
//! ([`Case::references`](crate::Case::references), `thirdbody cite CASE`). Every
//! `summary.json` and `results.csv` row carries the first three.

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

@article{hintermuller2002primal,
  author  = {Hinterm{\"u}ller, M. and Ito, K. and Kunisch, K.},
  title   = {The primal-dual active set strategy as a semismooth {Newton} method},
  journal = {SIAM Journal on Optimization},
  volume  = {13},
  number  = {3},
  pages   = {865--888},
  year    = {2002}
}

@book{tschoegl1989phenomenological,
  author    = {Tschoegl, N. W.},
  title     = {The Phenomenological Theory of Linear Viscoelastic Behavior},
  publisher = {Springer},
  year      = {1989}
}

@article{park1999interconversion,
  author  = {Park, S. W. and Schapery, R. A.},
  title   = {Methods of interconversion between linear viscoelastic material functions. {Part I}: a numerical method based on {Prony} series},
  journal = {International Journal of Solids and Structures},
  volume  = {36},
  pages   = {1653--1675},
  year    = {1999}
}

@book{mainardi2010fractional,
  author    = {Mainardi, Francesco},
  title     = {Fractional Calculus and Waves in Linear Viscoelasticity},
  publisher = {Imperial College Press},
  year      = {2010}
}

@article{trefethen2014trapezoidal,
  author  = {Trefethen, Lloyd N. and Weideman, J. A. C.},
  title   = {The exponentially convergent trapezoidal rule},
  journal = {SIAM Review},
  volume  = {56},
  number  = {3},
  pages   = {385--458},
  year    = {2014}
}

@book{tobolsky1960properties,
  author    = {Tobolsky, A. V.},
  title     = {Properties and Structure of Polymers},
  publisher = {Wiley},
  year      = {1960}
}

@article{kausel1981stiffness,
  author  = {Kausel, Eduardo and Ro{\"e}sset, Jos{\'e} M.},
  title   = {Stiffness matrices for layered soils},
  journal = {Bulletin of the Seismological Society of America},
  volume  = {71},
  number  = {6},
  pages   = {1743--1761},
  year    = {1981}
}
"#;

/// A published work: its BibTeX key in [`REFERENCES`] and a short citation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Work {
    /// The key of its entry in [`REFERENCES`].
    pub key: &'static str,
    /// Authors, venue and year, in one line.
    pub citation: &'static str,
}

impl Work {
    /// Its BibTeX entry (taken from [`REFERENCES`], the one place it is written).
    pub fn bibtex(&self) -> &'static str {
        let start = REFERENCES
            .find(&format!("{{{},", self.key))
            .and_then(|i| REFERENCES[..i].rfind('@'))
            .expect("every work has its entry in REFERENCES");
        let len = REFERENCES[start..]
            .find("\n}\n")
            .expect("every entry ends with a closing brace on its own line");
        &REFERENCES[start..start + len + 3]
    }
}

/// The paper whose model thirdbody solves.
pub const PAPER: Work = Work {
    key: "torskaya2023nonlinear",
    citation: "E. V. Torskaya & F. I. Stepanov, Lubricants 11 (2023) 333",
};
/// Love's stresses and displacements under uniform pressure on a rectangle.
pub const LOVE: Work = Work {
    key: "love1929stress",
    citation: "A. E. H. Love, Phil. Trans. R. Soc. Lond. A 228 (1929) 377-420",
};
/// DC-FFT.
pub const DC_FFT: Work = Work {
    key: "liu2000dcfft",
    citation: "S. Liu, Q. Wang & G. Liu, Wear 243 (2000) 101-111",
};
/// Conjugate gradients for contact problems.
pub const POLONSKY_KEER: Work = Work {
    key: "polonsky1999numerical",
    citation: "I. A. Polonsky & L. M. Keer, Wear 231 (1999) 206-219",
};
/// The semi-smooth Newton method on complementarity conditions.
pub const SEMISMOOTH_NEWTON: Work = Work {
    key: "hintermuller2002primal",
    citation: "M. Hintermüller, K. Ito & K. Kunisch, SIAM J. Optim. 13 (2002) 865-888",
};
/// A layered elastic medium's Fourier response.
pub const CHEN: Work = Work {
    key: "chen1971layered",
    citation: "W. T. Chen, Int. J. Eng. Sci. 9 (1971) 775-800",
};
/// The coated half-space's surface and stress response.
pub const OSULLIVAN_KING: Work = Work {
    key: "osullivan1988sliding",
    citation: "T. C. O'Sullivan & R. B. King, J. Tribol. 110 (1988) 235-240",
};
/// The cancellation-free form of the coated half-space's response.
pub const PERRIOT_BARTHEL: Work = Work {
    key: "perriot2004elastic",
    citation: "A. Perriot & E. Barthel, J. Mater. Res. 19 (2004) 600-608",
};
/// Linear viscoelastic material functions and their conversions.
pub const TSCHOEGL: Work = Work {
    key: "tschoegl1989phenomenological",
    citation: "N. W. Tschoegl, The Phenomenological Theory of Linear Viscoelastic Behavior, \
               Springer 1989",
};
/// Interconversion of Prony series.
pub const PARK_SCHAPERY: Work = Work {
    key: "park1999interconversion",
    citation: "S. W. Park & R. A. Schapery, Int. J. Solids Struct. 36 (1999) 1653-1675",
};
/// The fractional Zener body and its retardation spectrum.
pub const MAINARDI: Work = Work {
    key: "mainardi2010fractional",
    citation: "F. Mainardi, Fractional Calculus and Waves in Linear Viscoelasticity, \
               Imperial College Press 2010",
};
/// The trapezoidal rule on the line.
pub const TREFETHEN_WEIDEMAN: Work = Work {
    key: "trefethen2014trapezoidal",
    citation: "L. N. Trefethen & J. A. C. Weideman, SIAM Rev. 56 (2014) 385-458",
};
/// The box retardation spectrum.
pub const TOBOLSKY: Work = Work {
    key: "tobolsky1960properties",
    citation: "A. V. Tobolsky, Properties and Structure of Polymers, Wiley 1960",
};

/// Stiffness matrices of elastic layers.
pub const KAUSEL_ROESSET: Work = Work {
    key: "kausel1981stiffness",
    citation: "E. Kausel & J. M. Roësset, Bull. Seismol. Soc. Am. 71 (1981) 1743-1761",
};

/// Every work in [`REFERENCES`], in its order.
pub const WORKS: [Work; 14] = [
    PAPER,
    LOVE,
    DC_FFT,
    POLONSKY_KEER,
    CHEN,
    OSULLIVAN_KING,
    PERRIOT_BARTHEL,
    SEMISMOOTH_NEWTON,
    TSCHOEGL,
    PARK_SCHAPERY,
    MAINARDI,
    TREFETHEN_WEIDEMAN,
    TOBOLSKY,
    KAUSEL_ROESSET,
];

/// A work one computation relies on, and what for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Reference {
    /// The work.
    pub work: Work,
    /// What the computation takes from it (several uses joined by "; ").
    pub used_for: String,
}

impl Reference {
    /// `work` cited for `used_for`.
    pub fn new(work: Work, used_for: &str) -> Self {
        Reference {
            work,
            used_for: used_for.to_owned(),
        }
    }
}

/// `references` with each work once, in the order of its first citation, its uses
/// joined.
pub(crate) fn merged(references: Vec<Reference>) -> Vec<Reference> {
    let mut out: Vec<Reference> = Vec::new();
    for r in references {
        match out.iter_mut().find(|o| o.work == r.work) {
            Some(o) => {
                if !o.used_for.split("; ").any(|u| u == r.used_for) {
                    o.used_for.push_str("; ");
                    o.used_for.push_str(&r.used_for);
                }
            }
            None => out.push(r),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::test_cases::{parse, HERTZ as CASE};

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
        assert_eq!(keys.len(), WORKS.len());
        for (work, key) in WORKS.iter().zip(&keys) {
            assert_eq!(work.key, *key);
            assert!(work.bibtex().contains(&format!("{{{key},")));
            assert!(work.bibtex().ends_with("}\n"));
        }
        let mut sorted = keys.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), keys.len());
        assert_eq!(
            REFERENCES.matches('{').count(),
            REFERENCES.matches('}').count()
        );
    }

    fn keys(references: &[Reference]) -> Vec<&'static str> {
        references.iter().map(|r| r.work.key).collect()
    }

    const MAXWELL: &str = "[layer]\ncompliance = 0.02\nrelaxation_time = 1.0\n";

    #[test]
    fn a_maxwell_case_cites_the_paper_and_the_solver_it_will_use() {
        let creeping = parse(&format!("{CASE}{MAXWELL}").replace(
            "[loading]\nnormal_load = 5e-6\n",
            "[loading]\nnormal_load = 5e-6\nvelocity = 0.1\n",
        ));
        let refs = creeping.references(None);
        assert_eq!(
            keys(&refs),
            [PAPER.key, LOVE.key, DC_FFT.key, SEMISMOOTH_NEWTON.key]
        );
        assert!(
            refs[0].used_for.contains("Maxwell layer (eq. 2)"),
            "{refs:?}"
        );
        // At infinite velocity the linear Maxwell layer is a spring bed: conjugate
        // gradients, unless the case asks for Newton.
        let frozen = parse(&format!("{CASE}{MAXWELL}").replace(
            "[loading]\nnormal_load = 5e-6\n",
            "[loading]\nnormal_load = 5e-6\nvelocity = inf\n",
        ));
        assert_eq!(keys(&frozen.references(None))[3], POLONSKY_KEER.key);
        let asked = frozen.references(Some(crate::Method::SemismoothNewton));
        assert_eq!(keys(&asked)[3], SEMISMOOTH_NEWTON.key);
        // Without a layer: the paper's contact model, Love, DC-FFT, Polonsky–Keer.
        assert_eq!(
            keys(&parse(CASE).references(None)),
            [PAPER.key, LOVE.key, DC_FFT.key, POLONSKY_KEER.key]
        );
    }

    #[test]
    fn a_rheology_cites_its_discretisation_and_a_coating_its_kernels() {
        let fractional = parse(
            &format!(
                "{CASE}[layer]\nrheology = \"fractional_zener\"\nglassy_compliance = 0.01\n\
             compliance = 0.02\nretardation_time = 1.0\norder = 0.5\n"
            )
            .replace(
                "normal_load = 5e-6\n",
                "normal_load = 5e-6\nvelocity = 1.0\n",
            ),
        );
        let refs = fractional.references(None);
        let k = keys(&refs);
        assert!(
            k.contains(&MAINARDI.key) && k.contains(&TREFETHEN_WEIDEMAN.key),
            "{k:?}"
        );
        assert!(k.contains(&SEMISMOOTH_NEWTON.key), "{k:?}");
        let coated = parse(&format!(
            "{CASE}[coating]\nyoung = 2.0\npoisson = 0.3\nthickness = 0.05\n"
        ));
        let k = keys(&coated.references(None));
        for work in [CHEN, OSULLIVAN_KING, PERRIOT_BARTHEL, LOVE, POLONSKY_KEER] {
            assert!(k.contains(&work.key), "{} missing from {k:?}", work.key);
        }
        // Each work once, its uses joined.
        let mut sorted = k.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), k.len());
    }

    #[test]
    fn the_commit_is_a_full_hash_when_known() {
        if let Some(c) = commit() {
            assert_eq!(c.len(), 40);
        }
        assert!(!VERSION.is_empty());
    }
}
