//! Joining sweep folders (`thirdbody merge DIR... --out DIR`): typically the shards of
//! one sweep run as a cluster job array (`--shard K/N`, each into its own folder).
//! Every input must hold the same sweep (`sweep.json` equal); their records are copied
//! into the output folder, which may be new, one of the inputs, or an earlier merge of
//! the same sweep. A case finished in two inputs must have the same result (wall
//! times aside), otherwise the merge is refused. `results.csv` and the plot are then
//! rebuilt exactly as a run does, so a merge of shards equals the unsharded run.

use std::path::{Path, PathBuf};

use anyhow::Result;

use super::folder::{read_record, read_sweep_file, record_path, Folder, Record};
use super::run::finish;
use super::SweepError;
use crate::atomic::write_bytes;

/// What a merge did.
#[derive(Debug, Clone, PartialEq)]
pub struct MergeReport {
    /// Cases of the sweep.
    pub cases: usize,
    /// Cases with a record in the output now.
    pub finished: usize,
    /// Of which failed.
    pub failed: usize,
    /// Cases no input has finished.
    pub missing: usize,
    /// Records found in two or more inputs (with the same result).
    pub duplicates: usize,
    /// `results.csv`.
    pub results: PathBuf,
    /// `mu_vs_<key>.png`, if drawn.
    pub plot: Option<PathBuf>,
}

/// Merges the sweep folders `inputs` into `out`.
pub fn merge(inputs: &[PathBuf], out: &Path) -> Result<MergeReport> {
    let Some(first) = inputs.first() else {
        return Err(SweepError::spec("merge: give at least one sweep folder to merge").into());
    };
    let spec = read_sweep_file(first)?;
    for dir in &inputs[1..] {
        let other = read_sweep_file(dir)?;
        if !other.same_sweep(&spec) {
            return Err(SweepError::Folder(format!(
                "{} and {} hold different sweeps ({}); only shards of one sweep can be merged",
                first.display(),
                dir.display(),
                spec.difference(&other)
            ))
            .into());
        }
    }
    // Gather first, so that nothing is written when two inputs disagree.
    let mut chosen: Vec<Option<(Record, &Path)>> = vec![None; spec.cases.len()];
    let mut duplicates = 0;
    for dir in inputs {
        for (index, entry) in spec.cases.iter().enumerate() {
            let Some(record) = read_record(dir, &entry.case) else {
                continue;
            };
            match &chosen[index] {
                None => chosen[index] = Some((record, dir)),
                Some((kept, kept_dir)) => {
                    if !kept.same_result(&record) {
                        return Err(SweepError::Folder(format!(
                            "case {} has different results in {} and {}; remove the wrong \
                             record (cases/{}.json) and merge again",
                            entry.case,
                            kept_dir.display(),
                            dir.display(),
                            entry.case
                        ))
                        .into());
                    }
                    duplicates += 1;
                }
            }
        }
    }
    let folder = Folder::open(out, &spec)?;
    let mut to_write = Vec::new();
    for (record, from) in chosen.iter().flatten() {
        match read_record(folder.dir(), &record.case) {
            Some(existing) if existing.same_result(record) => {}
            Some(_) => {
                return Err(SweepError::Folder(format!(
                    "case {} already has a different result in {}; merge into a new folder",
                    record.case,
                    out.display()
                ))
                .into())
            }
            None => to_write.push((record, *from)),
        }
    }
    // Copied byte for byte: a record is never re-serialised.
    for (record, from) in to_write {
        let bytes = std::fs::read(record_path(from, &record.case))?;
        write_bytes(&record_path(folder.dir(), &record.case), &bytes)?;
    }
    let (collected, results, plot) = finish(folder.dir(), &spec)?;
    Ok(MergeReport {
        cases: spec.cases.len(),
        finished: collected.records.len(),
        failed: collected.failed(),
        missing: collected.missing,
        duplicates,
        results,
        plot,
    })
}
