//! A fuzzer in the tree: mutated bundled case files go through the parser
//! and, when they parse, a small-grid solve. Whatever the input, the outcome is a
//! parse or input error, a solver error, or a solution whose summary is finite: never
//! a panic, never a non-finite result. `PROPTEST_CASES` sets the budget (256 in the
//! suite; the 10-minute run reported in docs/validation.md used a large one).

use std::sync::atomic::{AtomicUsize, Ordering};

use proptest::prelude::*;

/// Outcomes so far: [parse errors, solver errors, solutions] (printed as the run goes,
/// so that a run shows how much of the budget reached the solver).
static OUTCOMES: [AtomicUsize; 3] = [
    AtomicUsize::new(0),
    AtomicUsize::new(0),
    AtomicUsize::new(0),
];

fn count(k: usize) {
    let n = OUTCOMES[k].fetch_add(1, Ordering::Relaxed) + 1;
    let total: usize = OUTCOMES.iter().map(|o| o.load(Ordering::Relaxed)).sum();
    if total % 1000 == 0 || (k == 2 && n == 1) {
        let [a, b, c] = [0, 1, 2].map(|i| OUTCOMES[i].load(Ordering::Relaxed));
        eprintln!("fuzz: {total} cases: {a} refused, {b} solver errors, {c} solved");
    }
}
use thirdbody::{solve, SolverParams};

const EXAMPLES: [&str; 11] = [
    include_str!("../../../../examples/paper_fig3.toml"),
    include_str!("../../../../examples/hertz.toml"),
    include_str!("../../../../examples/ellipsoid_si.toml"),
    include_str!("../../../../examples/paper_fig7.toml"),
    include_str!("../../../../examples/paper_fig10a.toml"),
    include_str!("../../../../examples/paper_fig12b_thick_coating.toml"),
    include_str!("../../../../examples/three_layer_coating.toml"),
    include_str!("../../../../examples/polymer_liner_rigid.toml"),
    include_str!("../../../../examples/fractional_zener_rubber.toml"),
    include_str!("../../../../examples/sweeps/zener_body_and_layer.toml"),
    include_str!("../../../../examples/hertz_line.toml"),
];

/// Values a hostile user might write in place of a number.
fn wild_value() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("0".to_string()),
        Just("-1".to_string()),
        Just("1e308".to_string()),
        Just("1e-308".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("nan".to_string()),
        Just("\"text\"".to_string()),
        Just("[1, 2, 3]".to_string()),
        Just("true".to_string()),
        // The body's words, in any key: a base or bonding where it does not belong.
        Just("\"rigid\"".to_string()),
        Just("\"half_space\"".to_string()),
        Just("\"frictionless\"".to_string()),
        Just("\"bonded\"".to_string()),
        // The viscoelastic substrate's words.
        Just("\"zener\"".to_string()),
        Just("\"elastic\"".to_string()),
        Just("\"prony\"".to_string()),
        // The line contact's words: a cylinder where a point slider was, one number
        // where a pair was.
        Just("\"cylinder\"".to_string()),
        Just("16".to_string()),
        Just("[1e-9, 1e9]".to_string()),
        Just("0.4999999".to_string()),
        Just("99999999999999999999".to_string()),
        (-300i32..300).prop_map(|e| format!("1e{e}")),
        any::<f64>().prop_map(|v| format!("{v:e}")),
        (0u64..100_000).prop_map(|v| v.to_string()),
    ]
}

/// One mutation of a case text: replace a value, drop a line, or duplicate one.
fn mutate(text: &str, line: usize, kind: u8, value: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let k = line % lines.len();
    match kind % 4 {
        0 | 1 => {
            if let Some((key, _)) = lines[k].split_once('=') {
                lines[k] = format!("{key}= {value}");
            }
        }
        2 => {
            lines.remove(k);
        }
        _ => {
            let copy = lines[k].clone();
            lines.insert(k, copy);
        }
    }
    lines.join("\n")
}

/// A small grid and no stresses, so that every solve is quick (one number of cells
/// for a line contact).
fn small(text: &str) -> String {
    let cells = if text.contains("\"cylinder\"") {
        "cells = 16"
    } else {
        "cells = [16, 16]"
    };
    text.lines()
        .take_while(|l| {
            !l.trim_start().starts_with("[stress]") && !l.trim_start().starts_with("[sweep")
        })
        .map(|l| {
            if l.trim_start().starts_with("cells") {
                cells.to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn mutated_cases_never_panic_or_give_non_finite_results(
        example in 0usize..EXAMPLES.len(),
        mutations in proptest::collection::vec((0usize..200, any::<u8>(), wild_value()), 1..4),
    ) {
        let mut text = small(EXAMPLES[example]);
        for (line, kind, value) in &mutations {
            text = mutate(&text, *line, *kind, value);
        }
        let parsed = thirdbody::case_file::parse_case_file(&text, &mut |_, _| {
            Err(thirdbody::Error::invalid("slider.file", "x", "no maps in this test"))
        });
        let Ok(file) = parsed else {
            count(0);
            return Ok(());
        };
        let params = SolverParams {
            max_iterations: 300,
            max_windows: 3,
            ..file.solver
        };
        let start = std::time::Instant::now();
        let solved = solve(&file.case, &params);
        let seconds = start.elapsed().as_secs_f64();
        if seconds > 5.0 {
            // Slow inputs are findings too (nothing may run past 60 s).
            eprintln!("fuzz: slow case ({seconds:.1} s):\n{text}\n---");
        }
        count(if solved.is_ok() { 2 } else { 1 });
        if let Ok(s) = solved {
            let summary = serde_json::to_value(s.summary()).unwrap();
            for (key, v) in summary.as_object().unwrap() {
                prop_assert!(
                    v.as_f64().is_none_or(f64::is_finite) && !v.is_null(),
                    "{key} = {v} for\n{text}"
                );
            }
        }
    }
}
