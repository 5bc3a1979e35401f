//! Atomic writes, the one place that writes a file under a temporary name and renames
//! it into place, so that a reader (or a killed run) never sees half a file:
//!
//! * [`write_with`] and [`write_bytes`]: one file, e.g. a plot or a sweep record; the
//!   target is either the old file or the complete new one.
//! * [`Staging`]: all the files of a run (`thirdbody solve`, `stress`, `reproduce`),
//!   renamed only when every one was written; if anything fails (or the staging is
//!   dropped without [`Staging::commit`]) the temporaries are removed, and the output
//!   folder too if this run created it, so no partial output is left behind.
//!
//! A temporary is `stem.tmp-<pid>.ext` beside its target ([`temp_path`]; the extension
//! is kept so that writers that choose their format by it still work);
//! [`is_temporary`] recognises one left by a killed run.

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// `stem.tmp-<pid>.ext` beside `path` (`stem.tmp-<pid>` without an extension).
pub fn temp_path(path: &Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or("file".into(), |s| s.to_string_lossy());
    let name = match path.extension() {
        Some(ext) => format!(
            "{stem}.tmp-{}.{}",
            std::process::id(),
            ext.to_string_lossy()
        ),
        None => format!("{stem}.tmp-{}", std::process::id()),
    };
    path.with_file_name(name)
}

/// Whether a file name is a temporary of [`temp_path`] (of any process), or of the
/// hidden form `.stem.tmp-<pid>.ext` that sweep folders of earlier versions used.
pub fn is_temporary(name: &str) -> bool {
    let name = name.strip_prefix('.').unwrap_or(name);
    let Some((stem, rest)) = name.rsplit_once(".tmp-") else {
        return false;
    };
    let pid = rest.split_once('.').map_or(rest, |(pid, _)| pid);
    !stem.is_empty() && !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit())
}

/// Writes `path` through `write`, which receives the temporary path, then renames
/// the temporary to `path`; on any error the temporary is removed.
pub fn write_with(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let temp = temp_path(path);
    let result = write(&temp).and_then(|()| {
        fs::rename(&temp, path)
            .with_context(|| format!("cannot move {} into place", path.display()))
    });
    if result.is_err() {
        // The writer may have left (part of) the file behind.
        let _ = fs::remove_file(&temp);
    }
    result
}

/// Writes `bytes` to `path` atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<()> {
    write_with(path, |temp| Ok(fs::write(temp, bytes)?))
        .with_context(|| format!("cannot write {}", path.display()))
}

/// The lock file of an output folder: the process id of the run writing it.
pub const LOCK_FILE: &str = "lock";

/// A folder's lock is held by another live run.
#[derive(Debug)]
pub struct LockHeld {
    /// The folder.
    pub dir: PathBuf,
    /// The process holding it.
    pub pid: u32,
}

impl std::fmt::Display for LockHeld {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} is being written by another run (process {}); wait for it to end or use \
             another --out folder",
            self.dir.display(),
            self.pid
        )
    }
}

impl std::error::Error for LockHeld {}

/// Writes our process id into `dir/lock`, unless a live process holds it (then the
/// error is a [`LockHeld`]); a lock left by a killed run is taken over.
pub fn take_lock(dir: &Path) -> Result<()> {
    use std::io::Write;
    let path = dir.join(LOCK_FILE);
    let me = std::process::id();
    for _ in 0..2 {
        match fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
        {
            Ok(mut f) => {
                writeln!(f, "{me}")?;
                return Ok(());
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                // A run that has just created the lock may not have written its id
                // yet: an empty lock is read again for a moment before it counts as
                // stale (taking it over at once let two sweeps started together
                // remove each other's files).
                let mut holder = None;
                for _ in 0..20 {
                    holder = fs::read_to_string(&path)
                        .ok()
                        .and_then(|t| t.trim().parse::<u32>().ok());
                    if holder.is_some() || !path.exists() {
                        break;
                    }
                    std::thread::sleep(std::time::Duration::from_millis(25));
                }
                if let Some(pid) = holder {
                    if pid != me && process_alive(pid) {
                        return Err(LockHeld {
                            dir: dir.to_path_buf(),
                            pid,
                        }
                        .into());
                    }
                }
                // Left by a run that was killed: take it over.
                let _ = fs::remove_file(&path);
            }
            Err(e) => return Err(e).with_context(|| format!("cannot create {}", path.display())),
        }
    }
    Err(anyhow::anyhow!("cannot take the lock {}", path.display()))
}

/// Whether process `pid` runs (Linux: `/proc/<pid>` exists; elsewhere unknown, and a
/// stale lock is assumed).
pub fn process_alive(pid: u32) -> bool {
    cfg!(target_os = "linux") && Path::new(&format!("/proc/{pid}")).exists()
}

/// Removes the temporaries in `dir` of runs that no longer live (a run killed while
/// writing leaves them: up to hundreds of MB).
pub fn remove_dead_temporaries(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let pid = name
            .rsplit_once(".tmp-")
            .and_then(|(_, rest)| rest.split('.').next()?.parse::<u32>().ok());
        if let Some(pid) = pid {
            if is_temporary(&name) && pid != std::process::id() && !process_alive(pid) {
                let _ = fs::remove_file(entry.path());
            }
        }
    }
}

/// Files of one run waiting to be renamed into place, in a folder locked for the run.
pub struct Staging {
    dir: PathBuf,
    created_dir: bool,
    /// (temporary path, final path)
    pending: Vec<(PathBuf, PathBuf)>,
    committed: bool,
}

impl Staging {
    /// Creates the output folder (and its parents) if needed and locks it (an error
    /// [`LockHeld`] if another live run writes it); removes temporaries that killed
    /// runs left there.
    pub fn new(dir: &Path) -> Result<Self> {
        let created_dir = !dir.exists();
        fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the output folder {}", dir.display()))?;
        if let Err(e) = take_lock(dir) {
            if created_dir {
                let _ = fs::remove_dir(dir);
            }
            return Err(e);
        }
        remove_dead_temporaries(dir);
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
        let temp = temp_path(&target);
        // Registered before writing so that a half-written file is removed too.
        self.pending.push((temp.clone(), target));
        write(&temp).with_context(|| format!("cannot write {}", self.dir.join(name).display()))
    }

    /// Renames every temporary to its final name; returns the final paths.
    pub fn commit(self) -> Result<Vec<PathBuf>> {
        self.commit_replacing(|_| false)
    }

    /// [`Staging::commit`], then removes the files of the folder that `earlier`
    /// recognises as outputs of an earlier run and this one did not write (a
    /// `compliance_map.png` of a layered case beside a layer-free summary).
    pub fn commit_replacing(mut self, earlier: impl Fn(&str) -> bool) -> Result<Vec<PathBuf>> {
        for (temp, target) in &self.pending {
            fs::rename(temp, target)
                .with_context(|| format!("cannot move {} into place", target.display()))?;
        }
        self.committed = true;
        let written: Vec<PathBuf> = self.pending.iter().map(|(_, t)| t.clone()).collect();
        if let Ok(entries) = fs::read_dir(&self.dir) {
            for entry in entries.flatten() {
                let name = entry.file_name().to_string_lossy().into_owned();
                if earlier(&name) && !written.contains(&entry.path()) {
                    let _ = fs::remove_file(entry.path());
                }
            }
        }
        Ok(written)
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        let _ = fs::remove_file(self.dir.join(LOCK_FILE));
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

    #[test]
    fn atomic_writes_leave_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("results.csv");
        write_bytes(&path, b"a,b\n").unwrap();
        write_bytes(&path, b"a,b\n1,2\n").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "a,b\n1,2\n");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
        let t = temp_path(&path);
        let name = t.file_name().unwrap().to_str().unwrap();
        assert!(name.starts_with("results.tmp-"), "{name}");
        assert!(is_temporary(name), "{name}");
        assert_eq!(t.extension().unwrap(), "csv");
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("mu.png");
        write_bytes(&path, b"old").unwrap();
        let e = write_with(&path, |t| {
            fs::write(t, "partial")?;
            anyhow::bail!("disk full")
        });
        assert!(e.is_err());
        assert_eq!(fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn temporaries_are_recognised_and_other_names_not() {
        for name in [
            "c0001.tmp-42.json",
            ".c0001.tmp-42.json",
            "lock.tmp-7",
            "a.b.tmp-1.png",
        ] {
            assert!(is_temporary(name), "{name}");
        }
        for name in [
            "c0001.json",
            "notes.tmp-x.txt",
            ".tmp-12.json",
            "a.tmp-.json",
            "lock",
        ] {
            assert!(!is_temporary(name), "{name}");
        }
    }
}
