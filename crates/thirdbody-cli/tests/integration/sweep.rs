//! The sweep engine end to end: the paper's Fig. 8 sweep, a sweep killed midway and
//! resumed, shards plus merge against the unsharded run, failed cases as failed rows,
//! and bad sweep specifications. The speed-up on 2 cores is the `sweep` bench.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use thirdbody_cli::sweep::{merge, run, RunOptions, Shard, Sweep};
use thirdbody_engine::atomic::is_temporary;

/// The paper's Fig. 8 case (sigmoid layer on a homogeneous half-space) on 32 x 32
/// cells without a [sweep] section; tests vary it (shared with the engine's tests).
const BASE: &str = include_str!("../../../thirdbody-engine/tests/data/sweep_base.toml");

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn thirdbody(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_thirdbody"))
        .args(args)
        .output()
        .unwrap()
}

fn write_case(dir: &Path, text: &str) -> PathBuf {
    let path = dir.join("case.toml");
    fs::write(&path, text).unwrap();
    path
}

fn options(out: &Path) -> RunOptions {
    RunOptions {
        out: out.to_path_buf(),
        shard: None,
        threads: None,
        retry_failed: false,
    }
}

/// results.csv as rows of column -> value, checking that every row is well formed.
fn read_results(dir: &Path) -> Vec<BTreeMap<String, String>> {
    let mut reader = csv::Reader::from_path(dir.join("results.csv")).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            assert_eq!(r.len(), header.len(), "row {r:?} does not match the header");
            header
                .iter()
                .cloned()
                .zip(r.iter().map(String::from))
                .collect()
        })
        .collect()
}

/// The numbers C and S of the printed `computed C (F failed), skipped S` line.
fn computed_and_skipped(stdout: &str) -> (usize, usize) {
    let number_after = |word: &str| -> usize {
        let rest = &stdout[stdout.find(word).unwrap_or_else(|| panic!("{stdout}")) + word.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    (number_after("computed "), number_after("skipped "))
}

fn record_files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    fs::read_dir(dir.join("cases"))
        .map(|d| {
            d.flatten()
                .map(|e| {
                    (
                        e.file_name().into_string().unwrap(),
                        fs::read(e.path()).unwrap(),
                    )
                })
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn paper_fig8_mu_falls_with_velocity_and_the_sigmoid_laws_lie_below_the_linear_one() {
    let case = examples().join("sweeps/paper_fig8.toml");
    let sweep = Sweep::from_file(&case, &[]).unwrap();
    assert_eq!(sweep.len(), 32);
    let out = tempfile::tempdir().unwrap();
    let start = Instant::now();
    let report = run(&sweep, &options(out.path()), &|_| {}).unwrap();
    println!(
        "Fig. 8 sweep, 32 cases at 128 x 128: {:.1} s",
        start.elapsed().as_secs_f64()
    );
    assert_eq!((report.computed, report.skipped), (32, 0));
    assert!(out.path().join("mu_vs_loading.velocity.png").exists());

    let rows = read_results(out.path());
    assert_eq!(rows.len(), 32);
    let mut curves: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for row in &rows {
        // Print every case, failed ones with their message, for the record.
        println!(
            "{:12} V' = {:<24} mu = {:<22} {} {}",
            row["variant"],
            row["loading.velocity"],
            row["friction_coefficient"],
            row["status"],
            row["error"]
        );
        if row["status"] == "ok" {
            curves.entry(row["variant"].clone()).or_default().push((
                row["loading.velocity"].parse().unwrap(),
                row["friction_coefficient"].parse().unwrap(),
            ));
        }
    }
    // Every case solves at 128 x 128, also at V' = 1e-4.
    assert!(rows.iter().all(|r| r["status"] == "ok"));
    let linear = &curves["linear"];
    for (name, curve) in &curves {
        assert_eq!(curve.len(), 8, "{name}");
        for w in curve.windows(2) {
            assert!(
                w[0].0 < w[1].0 && w[1].1 < w[0].1,
                "{name}: mu must fall with V': {w:?}"
            );
        }
    }
    for (k, &(v, mu_linear)) in linear.iter().enumerate() {
        let mu = |p0: &str| curves[&format!("p0 = {p0}")][k].1;
        // Below the linear law, and the more so the smaller p0 (the sooner the
        // compliance falls with pressure).
        assert!(
            mu("0.0025") < mu("0.005") && mu("0.005") < mu("0.0075") && mu("0.0075") < mu_linear,
            "V' = {v}: {} {} {} {mu_linear}",
            mu("0.0025"),
            mu("0.005"),
            mu("0.0075")
        );
    }
}

#[test]
fn a_killed_sweep_resumes_without_solving_any_case_twice() {
    let dir = tempfile::tempdir().unwrap();
    let case = write_case(dir.path(), &BASE.replace("[32, 32]", "[128, 128]"));
    let out = dir.path().join("out");
    let args = [
        "sweep",
        case.to_str().unwrap(),
        "--vary",
        "velocity=1e-3..1e-1:12",
        "--vary",
        "p0=0.0025,0.005,0.0075",
        "--out",
        out.to_str().unwrap(),
        "--threads",
        "1",
    ];
    let n = 36;
    let mut child = Command::new(env!("CARGO_BIN_EXE_thirdbody"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // A record being written when the kill came is left as a temporary
    // (`stem.tmp-<pid>.json`), not a finished record: the rerun removes it.
    let finished = |name: &String| !name.starts_with('.') && !is_temporary(name);
    // Kill it once a few cases are finished (temporaries do not count: a record
    // still being written when the kill came is not one).
    let deadline = Instant::now() + Duration::from_secs(120);
    // Names only while the sweep runs: a temporary listed may be renamed before it
    // could be read.
    let names = |dir: &Path| -> Vec<String> {
        fs::read_dir(dir.join("cases"))
            .map(|d| {
                d.flatten()
                    .filter_map(|e| e.file_name().into_string().ok())
                    .collect()
            })
            .unwrap_or_default()
    };
    while names(&out).iter().filter(|name| finished(name)).count() < 3 {
        assert!(Instant::now() < deadline, "no case finished in 2 minutes");
        assert!(
            child.try_wait().unwrap().is_none(),
            "the sweep ended before it was killed"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let before = record_files(&out);
    let k = before.keys().filter(|name| finished(name)).count();
    assert!(
        k >= 3 && k < n,
        "{k} of {n} records after the kill: not midway"
    );
    assert!(
        !out.join("results.csv").exists(),
        "the killed run never reached the end"
    );

    let rerun = thirdbody(&args);
    let stdout = String::from_utf8_lossy(&rerun.stdout);
    assert_eq!(
        rerun.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&rerun.stderr)
    );
    println!(
        "killed after {k} of {n} cases; rerun: {}",
        stdout.lines().next().unwrap_or("")
    );
    assert_eq!(computed_and_skipped(&stdout), (n - k, k), "{stdout}");
    // The records of the first run are untouched; no temporary, no lock is left.
    let after = record_files(&out);
    for (name, bytes) in before.iter().filter(|(name, _)| finished(name)) {
        assert_eq!(&after[name], bytes, "{name} was rewritten");
    }
    assert_eq!(after.len(), n);
    assert!(after
        .keys()
        .all(|name| name.ends_with(".json") && finished(name)));
    assert!(!out.join("lock").exists());
    // One well-formed, solved row per case, in product order.
    let rows = read_results(&out);
    assert_eq!(rows.len(), n);
    let spec: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.join("sweep.json")).unwrap()).unwrap();
    for (row, entry) in rows.iter().zip(spec["cases"].as_array().unwrap()) {
        assert_eq!(row["case"], entry["case"].as_str().unwrap());
        assert_eq!(row["status"], "ok", "{row:?}");
        assert!(row["friction_coefficient"].parse::<f64>().unwrap() > 0.0);
    }
    // A third run has nothing left to do.
    let again = thirdbody(&args);
    assert_eq!(
        computed_and_skipped(&String::from_utf8_lossy(&again.stdout)),
        (0, n)
    );
}

/// Byte-equal CSV texts; otherwise the differing cells are named.
fn assert_same_csv(got: &str, expected: &str) {
    if got == expected {
        return;
    }
    let cells = |t: &str| -> Vec<Vec<String>> {
        t.lines()
            .map(|l| l.split(',').map(String::from).collect())
            .collect()
    };
    let (g, e) = (cells(got), cells(expected));
    let mut diffs = Vec::new();
    for (r, (gr, er)) in g.iter().zip(&e).enumerate() {
        for (c, (gc, ec)) in gr.iter().zip(er).enumerate() {
            if gc != ec {
                diffs.push(format!(
                    "row {r} {}: {gc} != {ec}",
                    e[0].get(c).cloned().unwrap_or_default()
                ));
            }
        }
    }
    panic!(
        "results.csv differ ({} vs {} lines): {diffs:#?}",
        g.len(),
        e.len()
    );
}

#[test]
fn shards_merged_equal_the_unsharded_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let vary = [
        "velocity=1e-3..1e-1:3".to_string(),
        "p0=0.0025,0.005".to_string(),
    ];
    let sweep = Sweep::new(BASE, dir.path(), &vary).unwrap();
    let whole = dir.path().join("whole");
    run(&sweep, &options(&whole), &|_| {}).unwrap();
    let shard = |k: usize| {
        let out = dir.path().join(format!("shard{k}"));
        let report = run(
            &sweep,
            &RunOptions {
                shard: Some(Shard { k, n: 2 }),
                threads: Some(1),
                ..options(&out)
            },
            &|_| {},
        )
        .unwrap();
        assert_eq!((report.shard_cases, report.computed), (3, 3));
        out
    };
    let (one, two) = (shard(1), shard(2));
    // Shard 1/2 holds cases 0, 2, 4.
    let rows = read_results(&one);
    let ids: Vec<&str> = rows.iter().map(|r| &r["case"][..4]).collect();
    assert_eq!(ids, ["0000", "0002", "0004"]);

    // Alone, shard 1 leaves three cases missing.
    let partial = merge(std::slice::from_ref(&one), &dir.path().join("partial")).unwrap();
    assert_eq!((partial.finished, partial.missing), (3, 3));

    let merged = dir.path().join("merged");
    let report = merge(&[one.clone(), two.clone(), one.clone()], &merged).unwrap();
    assert_eq!(
        (report.finished, report.missing, report.duplicates),
        (6, 0, 3)
    );
    let expected = fs::read_to_string(whole.join("results.csv")).unwrap();
    assert_same_csv(
        &fs::read_to_string(merged.join("results.csv")).unwrap(),
        &expected,
    );
    // Through the command line too, merging into one of the shards.
    let output = thirdbody(&[
        "merge",
        one.to_str().unwrap(),
        two.to_str().unwrap(),
        "--out",
        two.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(0));
    assert_same_csv(
        &fs::read_to_string(two.join("results.csv")).unwrap(),
        &expected,
    );

    // A record that disagrees is refused, and so is another sweep's folder.
    let id = fs::read_dir(one.join("cases"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let text = fs::read_to_string(&id).unwrap();
    fs::write(
        &id,
        text.replace("\"status\": \"ok\"", "\"status\": \"failed\""),
    )
    .unwrap();
    let e = merge(&[one.clone(), whole.clone()], &dir.path().join("bad")).unwrap_err();
    assert!(e.to_string().contains("has different results in"), "{e}");
    assert!(!dir.path().join("bad").exists());
    let other = Sweep::new(BASE, dir.path(), &["velocity=1e-3,1e-2".to_string()]).unwrap();
    let other_dir = dir.path().join("other");
    run(&other, &options(&other_dir), &|_| {}).unwrap();
    let e = merge(&[whole.clone(), other_dir], &dir.path().join("bad")).unwrap_err();
    assert!(e.to_string().contains("hold different sweeps (it varies loading.velocity (2 values), not loading.velocity (3 values), layer.p0 (2 values))"), "{e}");
}

#[test]
fn failed_cases_become_failed_rows_and_are_not_retried_unless_asked() {
    let dir = tempfile::tempdir().unwrap();
    // delta = 1, p0' = 0.001, V' = 1e-4: the row relation folds and the solver refuses
    // (README, "How the model is read").
    let case = write_case(dir.path(), &BASE.replace("delta = 0.5", "delta = 1.0"));
    let out = dir.path().join("out");
    let args = [
        "sweep",
        case.to_str().unwrap(),
        "--vary",
        "layer.p0=0.001,0.05",
        "--vary",
        "velocity=1e-4",
        "--out",
        out.to_str().unwrap(),
    ];
    let first = thirdbody(&args);
    assert_eq!(first.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&first.stdout);
    assert!(
        stdout.contains("computed 2 (1 failed), skipped 0"),
        "{stdout}"
    );
    let rows = read_results(&out);
    assert_eq!(rows[0]["status"], "failed");
    assert!(
        rows[0]["error"].contains("row relation folds"),
        "{}",
        rows[0]["error"]
    );
    assert_eq!(rows[0]["friction_coefficient"], "");
    assert_eq!(rows[1]["status"], "ok");
    assert_eq!(rows[1]["error"], "");
    let again = thirdbody(&args);
    assert!(String::from_utf8_lossy(&again.stdout).contains("computed 0 (0 failed), skipped 2"));
    let mut retry = args.to_vec();
    retry.push("--retry-failed");
    let retried = thirdbody(&retry);
    assert!(String::from_utf8_lossy(&retried.stdout).contains("computed 1 (1 failed), skipped 1"));
}

/// Runs `thirdbody sweep` with `extra` arguments and checks exit code 2, one stderr line
/// containing every part, and no output folder.
fn assert_bad_sweep(case_text: &str, extra: &[&str], parts: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let case = write_case(dir.path(), case_text);
    let out = dir.path().join("out");
    let mut args = vec![
        "sweep",
        case.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    let output = thirdbody(&args);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{extra:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    for part in parts {
        assert!(stderr.contains(part), "{extra:?}: `{part}` not in {stderr}");
    }
    assert!(!out.exists(), "{extra:?} wrote {}", out.display());
}

#[test]
fn bad_sweep_specifications_are_named_and_nothing_is_written() {
    let bad = |extra: &[&str], parts: &[&str]| assert_bad_sweep(BASE, extra, parts);
    bad(
        &["--vary", "colour=1,2"],
        &["--vary colour: unknown key `colour`", "loading.velocity"],
    );
    bad(
        &["--vary", "layer.colour=1,2"],
        &["--vary layer.colour=1: unknown field `colour`", "`p0`"],
    );
    bad(
        &["--vary", "velocity=1e-4..1e-1:0"],
        &["--vary velocity", "n >= 2"],
    );
    bad(
        &["--vary", "velocity="],
        &["--vary velocity: no values given"],
    );
    bad(
        &["--vary", "velocity=1e-3,fast"],
        &["loading.velocity", "`fast` is not a number"],
    );
    bad(
        &["--vary", "velocity=0..1e-1:4"],
        &["both ends > 0", ":lin"],
    );
    bad(
        &["--vary", "velocity=1e-3..1e-1:x"],
        &["`x` is not a whole number"],
    );
    bad(
        &["--vary", "velocity=1e-3", "--vary", "loading.velocity=1e-2"],
        &["varied twice"],
    );
    bad(
        &["--vary", "delta=0.5,2"],
        &["sweep case 1 (layer.delta = 2)", "0 <= delta <= 1"],
    );
    bad(
        &["--vary", "velocity=1e-3", "--shard", "3/2"],
        &["--shard 3/2", "1 <= K <= N"],
    );
    bad(&[], &["nothing is varied"]);
    assert_bad_sweep(
        &format!("{BASE}\n[sweep]\nvary = 3\n"),
        &[],
        &["[sweep] vary must be a table"],
    );
    let coated = format!("{BASE}\n[coating]\nyoung = 3.0\npoisson = 0.3\nthickness = 0.02\n");
    assert_bad_sweep(
        &coated,
        &["--vary", "young=1,2"],
        &["ambiguous key `young`", "substrate.young or coating.young"],
    );
    assert_bad_sweep(
        &format!("{BASE}\n[sweep.vary]\nloading.velocity = \"1e-3..1e-2:1\"\n"),
        &[],
        &["[sweep.vary] loading.velocity", "n >= 2"],
    );
    assert_bad_sweep(
        &format!("{BASE}\n[sweep]\nplot_scale = \"logarithmic\"\n"),
        &["--vary", "velocity=1e-3,1e-2"],
        &[
            "[sweep] plot_scale = \"logarithmic\" is not a plot scale",
            "allowed: \"auto\", \"linear\", \"log\"",
        ],
    );
}

#[test]
fn a_folder_of_another_sweep_is_refused_and_left_alone() {
    let dir = tempfile::tempdir().unwrap();
    let case = write_case(dir.path(), BASE);
    let out = dir.path().join("out");
    let sweep = |vary: &str| {
        thirdbody(&[
            "sweep",
            case.to_str().unwrap(),
            "--vary",
            vary,
            "--out",
            out.to_str().unwrap(),
        ])
    };
    assert_eq!(sweep("velocity=1e-3,1e-2").status.code(), Some(0));
    let before = record_files(&out);
    let refused = sweep("velocity=1e-3,1e-1");
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("holds another sweep (the values of its varied keys differ)"),
        "{stderr}"
    );
    assert_eq!(record_files(&out), before);
    // A folder that is not a sweep folder is refused too.
    fs::write(dir.path().join("notes.txt"), "mine").unwrap();
    let output = thirdbody(&[
        "sweep",
        case.to_str().unwrap(),
        "--vary",
        "velocity=1e-3",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("is not a sweep folder"));
}

#[test]
fn dry_run_lists_the_cases_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let case = write_case(dir.path(), BASE);
    let out = dir.path().join("out");
    let output = thirdbody(&[
        "sweep",
        case.to_str().unwrap(),
        "--vary",
        "velocity=1e-4..1e-1:4",
        "--vary",
        "law=linear,sigmoid",
        "--vary",
        "delta=none,0.5",
        "--out",
        out.to_str().unwrap(),
        "--dry-run",
        "--shard",
        "2/3",
    ]);
    // law = linear with delta = 0.5 is not a valid case: refused before anything runs.
    assert_eq!(output.status.code(), Some(2));
    let output = thirdbody(&[
        "sweep",
        case.to_str().unwrap(),
        "--vary",
        "velocity=1e-4..1e-1:4",
        "--vary",
        "p0=0.001,0.002",
        "--out",
        out.to_str().unwrap(),
        "--dry-run",
        "--shard",
        "2/3",
    ]);
    assert_eq!(output.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.starts_with("8 cases, 3 in shard 2/3"), "{stdout}");
    assert!(
        stdout.contains("case\tloading.velocity\tlayer.p0\n"),
        "{stdout}"
    );
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 5, "{stdout}");
    assert!(
        lines[2].starts_with("0001-") && lines[2].ends_with("\t0.0001\t0.002"),
        "{stdout}"
    );
    assert!(lines[4].starts_with("0007-"), "{stdout}");
    assert!(!out.exists());
}

#[test]
fn bundled_sweep_examples_are_valid_sweeps() {
    let mut count = 0;
    for entry in fs::read_dir(examples().join("sweeps")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) == Some("toml") {
            let sweep = Sweep::from_file(&path, &[]);
            assert!(sweep.is_ok(), "{}: {}", path.display(), sweep.unwrap_err());
            count += 1;
        }
    }
    assert!(count >= 1);
}

#[test]
fn a_stress_section_in_the_base_case_adds_stress_columns() {
    // The Fig. 10 study: tau1_max against delta, from one sweep. Each row's stress
    // columns equal what `thirdbody solve` reports for that case alone.
    let dir = tempfile::tempdir().unwrap();
    let case = BASE.replace("normal_load = 25e-6", "normal_load = 5e-6") + "\n[stress]\n";
    let path = write_case(dir.path(), &case);
    let out = dir.path().join("sweep");
    let sweep = Sweep::from_file(&path, &["layer.delta=0.01,1".to_string()]).unwrap();
    let report = run(&sweep, &options(&out), &|_| {}).unwrap();
    assert_eq!(report.computed, 2);
    let rows = read_results(&out);
    let tau: Vec<f64> = rows
        .iter()
        .map(|r| r["stress_tau1_max"].parse().unwrap())
        .collect();
    assert!(tau[1] > tau[0], "tau1_max grows with delta: {tau:?}");
    for key in [
        "stress_tau1_max_x",
        "stress_tau1_max_z",
        "stress_sigma_x_min",
        "stress_sigma_x_max",
    ] {
        assert!(
            rows.iter()
                .all(|r| r[key].parse::<f64>().unwrap().is_finite()),
            "{key}"
        );
    }
    let single = dir.path().join("single.toml");
    fs::write(&single, case.replace("delta = 0.5", "delta = 1")).unwrap();
    let solved = dir.path().join("solved");
    let o = thirdbody(&[
        "solve",
        single.to_str().unwrap(),
        "--out",
        solved.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(solved.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["stress"]["tau1_max"].as_f64().unwrap(), tau[1]);
}

#[test]
fn a_sweep_varies_one_layer_of_a_stack() {
    // The polymer liner on its rigid backing, thinner and thinner: a thinner liner
    // on a rigid base is stiffer, so the same load presses the ball in less.
    let dir = tempfile::tempdir().unwrap();
    let text = fs::read_to_string(examples().join("polymer_liner_rigid.toml"))
        .unwrap()
        .replace("cells = [128, 128]", "cells = [32, 32]")
        .replace("[stress]\n", "");
    let case = write_case(dir.path(), &text);
    let out = dir.path().join("sweep");
    let run = thirdbody(&[
        "sweep",
        case.to_str().unwrap(),
        "--vary",
        "body.layers[0].thickness=0.1e-3,0.3e-3,1e-3",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let rows = read_results(&out);
    assert_eq!(rows.len(), 3);
    let depth = |thickness: &str| -> f64 {
        rows.iter()
            .find(|r| {
                r["body.layers[0].thickness"].parse::<f64>().unwrap()
                    == thickness.parse::<f64>().unwrap()
            })
            .unwrap_or_else(|| panic!("{thickness} missing: {rows:?}"))["penetration"]
            .parse()
            .unwrap()
    };
    let (thin, mid, thick) = (depth("0.1e-3"), depth("0.3e-3"), depth("1e-3"));
    assert!(thin < mid && mid < thick, "{thin} {mid} {thick}");
    // A key of a layer the stack does not have is refused before anything runs.
    let run = thirdbody(&[
        "sweep",
        case.to_str().unwrap(),
        "--vary",
        "body.layers[3].thickness=1e-3,2e-3",
        "--out",
        dir.path().join("bad").to_str().unwrap(),
    ]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("body.layers[3].thickness"), "{stderr}");
}

#[test]
fn a_sweep_of_line_contacts_gives_each_direct_solve() {
    // A cylinder (plane strain) over three loads per unit length: each row equals
    // what the library's solve of that case gives, and no row has a y column.
    let dir = tempfile::tempdir().unwrap();
    let base = fs::read_to_string(examples().join("hertz_line.toml"))
        .unwrap()
        .replace("cells = 1024", "cells = 256");
    let path = write_case(dir.path(), &base);
    let out = dir.path().join("sweep");
    let loads = ["5e-4", "1e-3", "2e-3"];
    let sweep =
        Sweep::from_file(&path, &[format!("loading.normal_load={}", loads.join(","))]).unwrap();
    let report = run(&sweep, &options(&out), &|_| {}).unwrap();
    assert_eq!(report.computed, 3);
    let rows = read_results(&out);
    assert_eq!(rows.len(), 3);
    for row in &rows {
        assert!(
            !row.contains_key("contact_y_min") && !row.contains_key("ny"),
            "{row:?}"
        );
        assert_eq!(row["contact"], "line");
        let load = &row["loading.normal_load"];
        let text = base.replace("normal_load = 1e-3", &format!("normal_load = {load}"));
        let file =
            thirdbody::case_file::parse_case_file(&text, &mut |_, _| unreachable!()).unwrap();
        let solution = thirdbody::solve(&file.case, &file.solver).unwrap();
        let s = solution.summary();
        for (key, value) in [
            ("normal_load", s.normal_load),
            ("penetration", s.penetration),
            ("max_pressure", s.max_pressure),
            ("contact_area", s.contact_area),
            ("contact_x_min", s.contact_x_min),
            ("contact_x_max", s.contact_x_max),
            ("friction_coefficient", s.friction_coefficient),
        ] {
            let got: f64 = row[key].parse().unwrap();
            assert!(
                (got - value).abs() <= 1e-12 * value.abs().max(1e-300),
                "load {load}, {key}: sweep {got}, solve {value}"
            );
        }
    }
    // cite takes the line case as it is.
    let cite = thirdbody(&["cite", path.to_str().unwrap()]);
    assert!(
        cite.status.success() && !cite.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&cite.stderr)
    );
}
