//! Refusing work that cannot fit in memory before it starts: the
//! library estimates what a solve and a stress request take
//! ([`thirdbody::Case::estimated_solve_bytes`],
//! [`thirdbody::stress::StressRequest::estimated_bytes`]); this module compares that
//! with the memory the machine has available (`MemAvailable` of `/proc/meminfo`, on
//! Linux; elsewhere no check is made) and words the refusal.

use thirdbody::stress::StressRequest;
use thirdbody::Case;

/// Bytes of memory available now, if the system says.
pub fn available_bytes() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

fn gib(bytes: f64) -> String {
    format!("{:.1} GiB", bytes / (1u64 << 30) as f64)
}

/// Peak bytes of one solve of `case` with the stresses `stress` asks for.
pub fn estimated_bytes(case: &Case, stress: Option<&StressRequest>) -> f64 {
    case.estimated_solve_bytes() + stress_bytes(case, stress)
}

fn stress_bytes(case: &Case, stress: Option<&StressRequest>) -> f64 {
    stress.map_or(0.0, |r| r.estimated_bytes(&case.body, case.grid.cells))
}

/// `Err(message)` when `workers` solves of `case` (with `stress`, if asked) would
/// not fit in `available` bytes.
pub fn check(
    case: &Case,
    stress: Option<&StressRequest>,
    workers: usize,
    available: Option<f64>,
) -> Result<(), String> {
    let Some(available) = available else {
        return Ok(());
    };
    let solve = case.estimated_solve_bytes();
    let stresses = stress_bytes(case, stress);
    let total = (solve + stresses) * workers.max(1) as f64;
    if total <= available {
        return Ok(());
    }
    let [nx, ny] = case.grid.cells;
    let cells = if case.slider.is_line() {
        format!("grid.cells = {nx}")
    } else {
        format!("grid.cells = [{nx}, {ny}]")
    };
    let what = if stresses > solve {
        format!(
            "the stresses asked for need about {} (the block's or planes' points: reduce \
             stress.depth_points or the sections)",
            gib(stresses)
        )
    } else {
        format!(
            "{cells} needs about {} per solve (reduce grid.cells)",
            gib(solve)
        )
    };
    let all = if workers > 1 {
        format!(" times {workers} workers, {} in all,", gib(total))
    } else {
        String::new()
    };
    Err(format!(
        "not enough memory: {what}{all} but {} is available",
        gib(available)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bundled Hertz case on `cells x cells`.
    fn case(cells: usize) -> Case {
        let text = include_str!("../../../examples/hertz.toml");
        let mut case = thirdbody::case_file::parse_case_file(text, &mut |_, _| unreachable!())
            .unwrap()
            .case;
        case.grid.cells = [cells, cells];
        case
    }

    #[test]
    fn a_grid_that_cannot_fit_is_refused_with_its_estimate() {
        let gib = (1u64 << 30) as f64;
        // A reported 16384² grid needs far more than a 24 GiB machine has.
        let e = check(&case(16384), None, 1, Some(24.0 * gib)).unwrap_err();
        assert!(
            e.contains("grid.cells = [16384, 16384]") && e.contains("GiB"),
            "{e}"
        );
        // 1024² fits; no estimate without a known amount of memory.
        assert!(check(&case(1024), None, 1, Some(24.0 * gib)).is_ok());
        assert!(check(&case(16384), None, 1, None).is_ok());
        // Two workers need twice the memory.
        let one = case(4096).estimated_solve_bytes();
        assert!(check(&case(4096), None, 1, Some(1.5 * one)).is_ok());
        assert!(check(&case(4096), None, 2, Some(1.5 * one)).is_err());
    }

    #[test]
    fn a_deep_block_is_refused_for_its_stresses() {
        // 128² x 4096 depths of 11 fields: 5.9 GB.
        let request = StressRequest {
            sections: Some(vec![thirdbody::stress::SectionKind::Block]),
            depth_points: 4096,
            ..StressRequest::default()
        };
        let c = case(128);
        let bytes = request.estimated_bytes(&c.body, c.grid.cells);
        assert!((bytes / 5.9e9 - 1.0).abs() < 0.01, "{bytes:e}");
        let e = check(&c, Some(&request), 1, Some(4.0 * (1u64 << 30) as f64)).unwrap_err();
        assert!(e.contains("stress.depth_points"), "{e}");
    }
}
