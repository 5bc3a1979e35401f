//! A sweep folder on disk (docs/sweeps.md, "Folder layout"):
//!
//! * `sweep.json`: what the sweep is (the base case as TOML text, the axes with every
//!   value, the case ids in product order). A rerun or a merge checks that it matches,
//!   so a folder is never mixed with another sweep's results.
//! * `cases/<id>.json`: one record per finished case (status `ok` with the summary, or
//!   `failed` with the error message). Records are written atomically
//!   ([`crate::atomic`]), so a record is either complete or absent, whenever the run
//!   is killed.
//! * `lock`: the process id of the run that is writing the folder, removed when it
//!   ends; a lock left by a killed run is taken over (on Linux a live holder is
//!   detected through `/proc`).
//! * `results.csv` and `mu_vs_<key>.png`: assembled from the records (see
//!   [`super::results`]).

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::atomic::{is_temporary, remove_dead_temporaries, take_lock, write_bytes, LockHeld};

use super::plot_scale::PlotScale;
use super::values::KeyValue;
use super::{Sweep, SweepError};

/// The sweep description file.
pub const SPEC_FILE: &str = "sweep.json";
/// The folder of case records.
pub const CASES_DIR: &str = "cases";
pub use crate::atomic::LOCK_FILE;
const FORMAT: &str = "thirdbody sweep 1";

/// `sweep.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepFile {
    /// Format tag.
    pub format: String,
    /// The base case without `[sweep]`, as TOML text.
    pub base_case: String,
    /// The axes of the product.
    pub axes: Vec<AxisEntry>,
    /// Every case in product order.
    pub cases: Vec<CaseEntry>,
    /// The mu axis of the plot; left out when automatic. A presentation choice, not
    /// part of what the sweep is: [`SweepFile::same_sweep`] ignores it.
    #[serde(default, skip_serializing_if = "PlotScale::is_auto")]
    pub plot_scale: PlotScale,
}

/// One axis in `sweep.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisEntry {
    /// Dotted key or `variant`.
    pub name: String,
    /// Its values came from log-spaced ranges.
    pub log_spaced: bool,
    /// Its values.
    pub levels: Vec<LevelEntry>,
}

/// One value of an axis in `sweep.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LevelEntry {
    /// As shown in `results.csv`.
    pub label: String,
    /// `[key, value]` pairs it sets; `null` removes the key.
    pub set: Vec<(String, Value)>,
}

impl LevelEntry {
    /// The number this value sets, when it sets one key to a number.
    pub fn number(&self) -> Option<f64> {
        match self.set.as_slice() {
            [(_, v)] => v.as_f64(),
            _ => None,
        }
    }
}

/// One case in `sweep.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseEntry {
    /// Its id (the record's file stem).
    pub case: String,
    /// The level of each axis.
    pub levels: Vec<usize>,
}

impl SweepFile {
    /// The description of `sweep`.
    pub fn of(sweep: &Sweep) -> SweepFile {
        let axes = sweep
            .axes()
            .iter()
            .map(|a| AxisEntry {
                name: a.name.clone(),
                log_spaced: a.log_spaced,
                levels: a
                    .levels
                    .iter()
                    .map(|l| LevelEntry {
                        label: l.label.clone(),
                        set: l
                            .set
                            .iter()
                            .map(|(k, v)| {
                                let v = match v {
                                    KeyValue::Remove => Value::Null,
                                    KeyValue::Set(v) => {
                                        serde_json::to_value(v).unwrap_or(Value::Null)
                                    }
                                };
                                (k.clone(), v)
                            })
                            .collect(),
                    })
                    .collect(),
            })
            .collect();
        SweepFile {
            format: FORMAT.to_string(),
            base_case: sweep.base_text(),
            axes,
            cases: (0..sweep.len())
                .map(|k| CaseEntry {
                    case: sweep.id(k).to_string(),
                    levels: sweep.levels(k),
                })
                .collect(),
            plot_scale: sweep.plot_scale(),
        }
    }

    /// Whether `other` describes the same sweep: everything but the plot's scale.
    pub fn same_sweep(&self, other: &SweepFile) -> bool {
        *self
            == SweepFile {
                plot_scale: self.plot_scale,
                ..other.clone()
            }
    }

    /// The labels of case `index`, one per axis.
    pub fn labels(&self, index: usize) -> Vec<String> {
        self.cases[index]
            .levels
            .iter()
            .zip(&self.axes)
            .map(|(&l, a)| a.levels[l].label.clone())
            .collect()
    }

    /// Why `other` is not the same sweep, in a few words.
    pub fn difference(&self, other: &SweepFile) -> String {
        let axes = |f: &SweepFile| {
            f.axes
                .iter()
                .map(|a| format!("{} ({} values)", a.name, a.levels.len()))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if self.format != other.format {
            format!("its format is {:?}, not {:?}", other.format, self.format)
        } else if self.base_case != other.base_case {
            "its base case differs".to_string()
        } else if axes(self) != axes(other) {
            format!("it varies {}, not {}", axes(other), axes(self))
        } else {
            "the values of its varied keys differ".to_string()
        }
    }
}

/// How a case ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Solved; the record holds its summary.
    Ok,
    /// The solver refused or failed; the record holds the message.
    Failed,
}

impl Status {
    /// `ok` or `failed`, as in `results.csv`.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Failed => "failed",
        }
    }
}

/// `cases/<id>.json`: the result of one case.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// The case id.
    pub case: String,
    /// Its index in the product.
    pub index: usize,
    /// Its values, one label per axis.
    pub settings: Vec<String>,
    /// How it ended.
    pub status: Status,
    /// The error message of a failed case.
    pub error: Option<String>,
    /// The summary of a solved case (as `summary.json` of `thirdbody solve`).
    pub summary: Option<Value>,
    /// Wall time of the case (kernel set-up and solve).
    pub solve_seconds: f64,
}

impl Record {
    /// The same outcome, ignoring wall times.
    pub fn same_result(&self, other: &Record) -> bool {
        let strip = |r: &Record| {
            let mut r = r.clone();
            r.solve_seconds = 0.0;
            if let Some(Value::Object(m)) = &mut r.summary {
                m.remove("solve_seconds");
            }
            r
        };
        strip(self) == strip(other)
    }
}

/// Reads `dir/sweep.json`.
pub fn read_sweep_file(dir: &Path) -> Result<SweepFile> {
    let path = dir.join(SPEC_FILE);
    let text = fs::read_to_string(&path).map_err(|e| {
        SweepError::Folder(format!(
            "{} is not a sweep folder: cannot read {}: {e}",
            dir.display(),
            path.display()
        ))
    })?;
    let file: SweepFile = serde_json::from_str(&text).map_err(|e| {
        SweepError::Folder(format!("{} is not a valid sweep file: {e}", path.display()))
    })?;
    if file.format != FORMAT {
        return Err(SweepError::Folder(format!(
            "{} has format {:?}; this thirdbody reads {FORMAT:?}",
            path.display(),
            file.format
        ))
        .into());
    }
    Ok(file)
}

/// Reads the record of case `id` in `dir`, if present and well formed.
pub fn read_record(dir: &Path, id: &str) -> Option<Record> {
    let text = fs::read_to_string(record_path(dir, id)).ok()?;
    let record: Record = serde_json::from_str(&text).ok()?;
    (record.case == id).then_some(record)
}

/// `dir/cases/<id>.json`.
pub fn record_path(dir: &Path, id: &str) -> PathBuf {
    dir.join(CASES_DIR).join(format!("{id}.json"))
}

/// Writes a record atomically.
pub fn write_record(dir: &Path, record: &Record) -> Result<()> {
    let mut text = serde_json::to_string_pretty(record)?;
    text.push('\n');
    write_bytes(&record_path(dir, &record.case), text.as_bytes())
}

/// The output folder of a run, locked while the run writes it.
#[derive(Debug)]
pub struct Folder {
    dir: PathBuf,
}

impl Folder {
    /// Opens (creating it if needed) the folder of `spec`: refuses a folder that holds
    /// another sweep or is not a sweep folder, or that another live run is writing.
    pub fn open(dir: &Path, spec: &SweepFile) -> Result<Folder> {
        check_usable(dir, spec)?;
        fs::create_dir_all(dir.join(CASES_DIR))
            .with_context(|| format!("cannot create the sweep folder {}", dir.display()))?;
        take_lock(dir).map_err(|e| match e.downcast_ref::<LockHeld>() {
            Some(held) => SweepError::Folder(held.to_string()).into(),
            None => e,
        })?;
        let folder = Folder {
            dir: dir.to_path_buf(),
        };
        remove_dead_temporaries(&dir.join(CASES_DIR));
        remove_dead_temporaries(dir);
        // Written when new, and again when only the plot's scale changed (so that a merge
        // draws the plot as this run does).
        if read_sweep_file(dir).ok().as_ref() != Some(spec) {
            let mut text = serde_json::to_string_pretty(spec)?;
            text.push('\n');
            write_bytes(&dir.join(SPEC_FILE), text.as_bytes())?;
        }
        Ok(folder)
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = fs::remove_file(self.dir.join(LOCK_FILE));
    }
}

fn check_usable(dir: &Path, spec: &SweepFile) -> Result<()> {
    if !dir.exists() {
        return Ok(());
    }
    if !dir.is_dir() {
        return Err(SweepError::Folder(format!(
            "--out {} exists and is not a folder",
            dir.display()
        ))
        .into());
    }
    if dir.join(SPEC_FILE).exists() {
        let stored = read_sweep_file(dir)?;
        if !stored.same_sweep(spec) {
            return Err(SweepError::Folder(format!(
                "{} holds another sweep ({}); use another --out folder, or delete it to \
                 start again",
                dir.display(),
                spec.difference(&stored)
            ))
            .into());
        }
        return Ok(());
    }
    if !only_leftovers(dir) {
        // A run that started in this folder may have written its sweep.json and
        // first records since the look above (two sweeps started together): look
        // again at the one file that decides.
        if dir.join(SPEC_FILE).exists() {
            return check_usable(dir, spec);
        }
        return Err(SweepError::Folder(format!(
            "{} exists, is not empty and is not a sweep folder (no {SPEC_FILE}); choose \
             another --out folder",
            dir.display()
        ))
        .into());
    }
    Ok(())
}

/// Whether `dir` holds nothing, or only what a run killed before writing `sweep.json`
/// leaves (a lock, an empty `cases` folder, temporaries).
fn only_leftovers(dir: &Path) -> bool {
    let Ok(entries) = fs::read_dir(dir) else {
        return false;
    };
    entries.flatten().all(|e| {
        let name = e.file_name().to_string_lossy().into_owned();
        name == LOCK_FILE
            || is_temporary(&name)
            || (name == CASES_DIR && fs::read_dir(e.path()).is_ok_and(|mut d| d.next().is_none()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lock_of_a_live_process_is_respected_and_a_stale_one_taken_over() {
        let dir = tempfile::tempdir().unwrap();
        let spec = SweepFile {
            format: FORMAT.into(),
            base_case: "x".into(),
            axes: vec![],
            cases: vec![],
            plot_scale: PlotScale::Auto,
        };
        // Process 1 (init) is alive on Linux.
        fs::write(dir.path().join(LOCK_FILE), "1\n").unwrap();
        let e = Folder::open(dir.path(), &spec);
        if cfg!(target_os = "linux") {
            let e = e.unwrap_err().to_string();
            assert!(
                e.contains("being written by another run (process 1)"),
                "{e}"
            );
        }
        // A pid that cannot exist (above the kernel's maximum, 2^22).
        fs::write(dir.path().join(LOCK_FILE), "99999999\n").unwrap();
        let folder = Folder::open(dir.path(), &spec).unwrap();
        let held = fs::read_to_string(dir.path().join(LOCK_FILE)).unwrap();
        assert_eq!(held.trim(), std::process::id().to_string());
        drop(folder);
        assert!(!dir.path().join(LOCK_FILE).exists());
        // Same sweep again: fine; another plot scale: the same sweep, recorded.
        Folder::open(dir.path(), &spec).unwrap();
        let log = SweepFile {
            plot_scale: PlotScale::Log,
            ..spec.clone()
        };
        drop(Folder::open(dir.path(), &log).unwrap());
        assert_eq!(read_sweep_file(dir.path()).unwrap(), log);
        // Another sweep: refused.
        let other = SweepFile {
            base_case: "y".into(),
            ..spec
        };
        let e = Folder::open(dir.path(), &other).unwrap_err().to_string();
        assert!(
            e.contains("holds another sweep (its base case differs)"),
            "{e}"
        );
    }
}
