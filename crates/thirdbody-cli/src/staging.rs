//! All-or-nothing output: every file of a run is first written under a temporary
//! name (`stem.tmp-<pid>.ext`, keeping the extension so that writers that choose
//! their format by extension still work) in the output folder, and renamed to its
//! final name only when all of them were written. If anything fails (or the staging
//! is dropped without [`Staging::commit`]), the temporaries are removed, and the
//! output folder too if this run created it, so no partial output is left behind.

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// Files of one run waiting to be renamed into place.
pub struct Staging {
    dir: PathBuf,
    created_dir: bool,
    /// (temporary path, final path)
    pending: Vec<(PathBuf, PathBuf)>,
    committed: bool,
}

impl Staging {
    /// Creates the output folder (and its parents) if needed.
    pub fn new(dir: &Path) -> Result<Self> {
        let created_dir = !dir.exists();
        fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the output folder {}", dir.display()))?;
        Ok(Staging {
            dir: dir.to_path_buf(),
            created_dir,
            pending: Vec::new(),
            committed: false,
        })
    }

    /// Writes the file `name` through `write`, which receives the temporary path.
    pub fn write(&mut self, name: &str, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
        let target = self.dir.join(name);
        let stem = Path::new(name)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or(name);
        let temp_name = match Path::new(name).extension().and_then(|e| e.to_str()) {
            Some(ext) => format!("{stem}.tmp-{}.{ext}", std::process::id()),
            None => format!("{stem}.tmp-{}", std::process::id()),
        };
        let temp = self.dir.join(temp_name);
        // Registered before writing so that a half-written file is removed too.
        self.pending.push((temp.clone(), target));
        write(&temp).with_context(|| format!("cannot write {}", self.dir.join(name).display()))
    }

    /// Renames every temporary to its final name; returns the final paths.
    pub fn commit(mut self) -> Result<Vec<PathBuf>> {
        for (temp, target) in &self.pending {
            fs::rename(temp, target)
                .with_context(|| format!("cannot move {} into place", target.display()))?;
        }
        self.committed = true;
        Ok(self.pending.iter().map(|(_, t)| t.clone()).collect())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if self.committed {
            return;
        }
        for (temp, _) in &self.pending {
            let _ = fs::remove_file(temp);
        }
        if self.created_dir {
            // Fails (harmlessly) unless the folder is empty.
            let _ = fs::remove_dir(&self.dir);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nothing_is_left_when_a_write_fails() {
        let root = tempfile::tempdir().unwrap();
        let out = root.path().join("a/out");
        {
            let mut s = Staging::new(&out).unwrap();
            s.write("one.json", |p| Ok(fs::write(p, "{}")?)).unwrap();
            let e = s.write("two.npy", |p| {
                fs::write(p, "partial")?;
                anyhow::bail!("disk full")
            });
            assert!(e.is_err());
            assert!(out
                .join("one.tmp-".to_string() + &std::process::id().to_string() + ".json")
                .exists());
        }
        assert!(!out.exists(), "the folder this run created is removed");
        assert!(root.path().join("a").exists());
    }

    #[test]
    fn commit_renames_everything_and_keeps_other_files() {
        let root = tempfile::tempdir().unwrap();
        fs::write(root.path().join("notes.txt"), "mine").unwrap();
        let mut s = Staging::new(root.path()).unwrap();
        s.write("summary.json", |p| Ok(fs::write(p, "{}")?))
            .unwrap();
        s.write("pressure.csv", |p| Ok(fs::write(p, "x,y,pressure\n")?))
            .unwrap();
        let done = s.commit().unwrap();
        assert_eq!(done.len(), 2);
        let mut names: Vec<_> = fs::read_dir(root.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["notes.txt", "pressure.csv", "summary.json"]);
    }

    #[test]
    fn a_dropped_staging_leaves_an_existing_folder_alone() {
        let root = tempfile::tempdir().unwrap();
        fs::write(root.path().join("notes.txt"), "mine").unwrap();
        {
            let mut s = Staging::new(root.path()).unwrap();
            s.write("gap.npy", |p| Ok(fs::write(p, "x")?)).unwrap();
        }
        let names: Vec<_> = fs::read_dir(root.path()).unwrap().collect();
        assert_eq!(names.len(), 1);
        assert!(root.path().join("notes.txt").exists());
    }
}
