//! The coated body's stress kernels of coatings much thinner than a cell
//! (the thin film: Love's kernels and the two carriers, without the remainder) and
//! much thicker than the window (the coating's half-space plus a constant), against
//! the full expansion on both sides of each switch, and against the independent
//! limits (Love's kernels of the substrate as h1 -> 0, of the coating as h1 -> inf).

use thirdbody::stress::StressMethod;
use thirdbody::stress::{
    HomogeneousStressKernels, InfluenceTable, LayeredStressKernels, OffsetLattice, Side,
    StressKernels,
};

mod coated_tables;

use coated_tables::*;

/// A centred lattice of `n x n` offsets, cell 1.
fn lattice(n: usize) -> OffsetLattice {
    square_lattice(n, -(((n - 1) / 2) as f64))
}

/// Largest difference over all components and offsets, relative to `scale`.
fn difference(a: &InfluenceTable, b: &InfluenceTable, scale: f64) -> f64 {
    max_difference(a, b) / scale
}

#[test]
#[ignore = "measurement: prints the thin-film error against the sub-cell split"]
fn thin_film_error_survey() {
    let l = lattice(9);
    for ratio in [0.3, 3.0, 30.0] {
        for h1 in [
            1.0 / 16.0,
            1.0 / 64.0,
            1.0 / 256.0,
            1.0 / 1024.0,
            1.0 / 4096.0,
        ] {
            let k = coated_kernels(elastic(ratio, 0.3), h1, elastic(1.0, 0.3), Side::Above);
            let chosen = k.method(&l);
            let mut worst = 0.0f64;
            for (z, side) in [
                (0.0, Side::Above),
                (0.5 * h1, Side::Above),
                (h1, Side::Above),
                (h1, Side::Below),
                (2.0 * h1, Side::Below),
                (1.0, Side::Below),
            ] {
                let k = LayeredStressKernels {
                    interface_side: side,
                    ..k.clone()
                };
                let sub = table(&k, z, &l, StressMethod::SubCell);
                let thin = table(&k, z, &l, StressMethod::ThinFilm);
                worst = worst.max(difference(&sub, &thin, peak(&sub)));
            }
            println!("E1/E2 {ratio:5} h1 {h1:9.6}: worst {worst:.2e}, chosen {chosen:?}, criterion {:.2e}", k.remainder_at_grid_scale(1.0));
        }
    }
}

/// The switch to the thin film is continuous to 1e-3 of the peak: one cell's
/// coefficients (9 x 9 offsets) by the thin film and by the sub-cell split (what a
/// solve uses above the switch; it equals the full expansion to 1e-9 of the peak,
/// `coated_stress_sub_cell.rs`) just on either side of it (E1/E2 = 3, the
/// criterion is 2.6e-5 at h1 = cell / 4096). The full expansion itself sums
/// `~5 cell / h1` alias orders here, too slow for a test.
#[test]
fn thin_film_switch_is_continuous() {
    let l = lattice(9);
    for h1 in [1.0 / 2048.0, 1.0 / 4096.0, 1.0 / 8192.0] {
        for (z, side) in [
            (0.0, Side::Above),
            (h1, Side::Above),
            (h1, Side::Below),
            (0.5, Side::Below),
        ] {
            let k = coated_kernels(elastic(3.0, 0.3), h1, elastic(1.0, 0.3), side);
            let sub = table(&k, z, &l, StressMethod::SubCell);
            let thin = table(&k, z, &l, StressMethod::ThinFilm);
            let e = difference(&sub, &thin, peak(&sub));
            println!(
                "h1 {h1:.3e} z {z:.3e} {side:?}: {e:.2e} ({:?})",
                k.method(&l)
            );
            assert!(e < 1e-3, "h1 {h1}, z {z} {side:?}: {e:.2e}");
        }
    }
}

/// The thin film against the independent h1 -> 0 limit: in the substrate, Love's
/// kernels of the substrate; in the coating at the surface, the stresses of the
/// coating strained with the substrate's surface (sigma_z and the strains
/// continuous; the jump formula of docs/architecture.md, numerics). The difference
/// is O(h1 / cell).
#[test]
fn thin_film_tends_to_the_substrate_half_space() {
    let l = lattice(9);
    let (e1, e2) = (elastic(3.0, 0.25), elastic(1.0, 0.35));
    for h1 in [1e-8, 1e-12] {
        let k = coated_kernels(e1, h1, e2, Side::Below);
        assert_eq!(k.method(&l), StressMethod::ThinFilm);
        let love = |z: f64| {
            let mut t = InfluenceTable::default();
            HomogeneousStressKernels { material: e2 }.fill(z, &l, &mut t);
            t
        };
        // Below the film.
        for z in [h1, 0.3, 1.0] {
            let (thin, reference) = (table(&k, z, &l, StressMethod::ThinFilm), love(z));
            let e = difference(&thin, &reference, peak(&reference));
            println!("h1 {h1:e}, substrate z {z}: {e:.2e}");
            assert!(e < 1e-6, "h1 {h1}, z {z}: {e:.2e}");
        }
        // In the film: the substrate's surface strains in the coating's material.
        let surface = love(0.0);
        let thin = table(&k, 0.0, &l, StressMethod::ThinFilm);
        let mut worst = 0.0f64;
        for n in 0..l.cols * l.rows {
            let [sx, sy, sz, txy] = [0, 1, 2, 3].map(|c| surface.values[c][n]);
            let (e, nu) = (e2.young, e2.poisson);
            let exx = (sx - nu * (sy + sz)) / e;
            let eyy = (sy - nu * (sx + sz)) / e;
            let gxy = txy * (1.0 + nu) / e;
            let (ec, nc) = (e1.young, e1.poisson);
            let m = ec / (1.0 - nc * nc);
            let expected = [
                m * (exx + nc * eyy) + nc / (1.0 - nc) * sz,
                m * (eyy + nc * exx) + nc / (1.0 - nc) * sz,
                sz,
                gxy * ec / (1.0 + nc),
                0.0,
                0.0,
            ];
            for (c, want) in expected.iter().enumerate() {
                worst = worst.max((thin.values[c][n] - want).abs());
            }
        }
        let e = worst / peak(&surface);
        println!("h1 {h1:e}, coating at the surface: {e:.2e}");
        assert!(e < 1e-6, "h1 {h1}: {e:.2e}");
    }
}

/// A coating much thicker than the window: the switch (diagonal below 1e-4 h1) is
/// continuous, and the kernels tend to Love's of the coating.
#[test]
fn thick_coating_switch_is_continuous_and_tends_to_the_coating_half_space() {
    let l = lattice(9);
    let (e1, e2) = (elastic(3.0, 0.25), elastic(1.0, 0.35));
    // The lattice's diagonal: (4 + 1/2) sqrt 2 cells.
    let diagonal = 4.5 * 2f64.sqrt();
    for s in [1e-3, 2e-4, 5e-5] {
        let h1 = diagonal / s;
        for (z, side) in [
            (0.0, Side::Above),
            (0.7, Side::Above),
            (3.0, Side::Above),
            (h1, Side::Above),
            (h1, Side::Below),
        ] {
            let k = coated_kernels(e1, h1, e2, side);
            let full = table(&k, z, &l, StressMethod::Full);
            let thick = table(&k, z, &l, StressMethod::ThickCoating);
            let e = difference(&full, &thick, peak(&full));
            let mut coating = InfluenceTable::default();
            HomogeneousStressKernels { material: e1 }.fill(z.min(0.5 * h1), &l, &mut coating);
            let to_love = difference(&thick, &coating, peak(&thick));
            println!(
                "diagonal/h1 {s:e} z {z:.3e} {side:?}: thick vs full {e:.2e}, vs coating Love {to_love:.2e} ({:?})",
                k.method(&l)
            );
            assert!(thick.values.iter().flatten().all(|v| v.is_finite()));
            if z < h1 {
                // The far interface adds O((W / h1)^2) of the peak.
                assert!(to_love < 10.0 * s * s, "s {s}, z {z}: {to_love:.2e}");
            }
            // Continuity at and around the switch: O((W / h1)^2). At the interface
            // (thousands of cells deep) the full expansion's Love corner sums have
            // lost digits (4.8e-4 at 6.4e3 cells); the thick method takes the
            // kernel's constant there and is only required finite.
            if z < h1 {
                assert!(e < 1e-6 + 10.0 * s * s, "s {s}, z {z} {side:?}: {e:.2e}");
            }
        }
    }
}

/// Very thick and very thin coatings fill their kernels in bounded time and with
/// finite values (they hung: a table of 1e10 panels at h1 = 1e6, 129^2 aliases per
/// wavenumber at h1 = 1e-12).
#[test]
fn extreme_thicknesses_are_finite() {
    let l = lattice(33);
    for h1 in [1e-12, 1e-8, 1e6, 1e100] {
        for (z, side) in [
            (0.0, Side::Above),
            (h1, Side::Above),
            (h1, Side::Below),
            (2.0, Side::Below),
        ] {
            let k = coated_kernels(elastic(3.0, 0.3), h1, elastic(1.0, 0.3), side);
            let mut t = InfluenceTable::default();
            k.fill(z, &l, &mut t);
            assert!(
                t.values.iter().flatten().all(|v| v.is_finite()),
                "h1 {h1}, z {z} {side:?}"
            );
        }
    }
}
