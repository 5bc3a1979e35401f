//! Reading a slider height map from a file: CSV (rows of numbers separated by
//! commas, one row per y, first row at the smallest y) or NPY (a 2-D float64
//! array of shape (ny, nx), rows along y). Paths are relative to the case file's
//! folder. The heights themselves (finite, rectangular) are checked by the library.

use std::path::Path;

use ndarray::Array2;
use thirdbody::{Error, HeightMap};

/// Loads `file` (resolved against `base`, the case file's folder) with sample
/// spacing `cell_size`. Read or format errors name `slider.file`.
pub fn load(base: &Path, file: &str, cell_size: f64) -> thirdbody::Result<HeightMap> {
    let path = base.join(file);
    let bad = |why: String| {
        Error::invalid(
            "slider.file",
            format!("\"{}\"", path.display()),
            &format!(
                "a readable CSV (rows of numbers, rows along y) or 2-D float64 NPY file ({})",
                why.replace('\n', " ")
            ),
        )
    };
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (nx, ny, heights) = match extension.as_deref() {
        Some("csv") | Some("txt") => read_csv(&path).map_err(bad)?,
        Some("npy") => read_npy(&path).map_err(bad)?,
        _ => return Err(bad("the name must end in .csv or .npy".into())),
    };
    Ok(HeightMap {
        nx,
        ny,
        cell_size,
        heights,
    })
}

fn read_csv(path: &Path) -> Result<(usize, usize, Vec<f64>), String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_path(path)
        .map_err(|e| e.to_string())?;
    let mut heights = Vec::new();
    let (mut nx, mut ny) = (0, 0);
    for record in reader.records() {
        let record = record.map_err(|e| e.to_string())?;
        for (i, field) in record.iter().enumerate() {
            let value: f64 = field.parse().map_err(|_| {
                format!(
                    "row {}, column {}: \"{field}\" is not a number",
                    ny + 1,
                    i + 1
                )
            })?;
            heights.push(value);
        }
        nx = record.len();
        ny += 1;
    }
    if ny == 0 {
        return Err("the file holds no numbers".into());
    }
    Ok((nx, ny, heights))
}

fn read_npy(path: &Path) -> Result<(usize, usize, Vec<f64>), String> {
    let array: Array2<f64> = ndarray_npy::read_npy(path).map_err(|e| e.to_string())?;
    let (ny, nx) = array.dim();
    // `iter` visits in logical (row-major) order whatever the memory layout.
    Ok((nx, ny, array.iter().copied().collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_rows_run_along_y() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("m.csv"), "# heights\n1, 2, 3\n4,5,6\n").unwrap();
        let m = load(dir.path(), "m.csv", 0.5).unwrap();
        assert_eq!((m.nx, m.ny, m.cell_size), (3, 2, 0.5));
        // Second row (larger y), first column: index j * nx + i = 3.
        assert_eq!(m.heights, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    }

    #[test]
    fn npy_shape_is_ny_by_nx() {
        let dir = tempfile::tempdir().unwrap();
        let a = Array2::from_shape_fn((2, 3), |(j, i)| (10 * j + i) as f64);
        ndarray_npy::write_npy(dir.path().join("m.npy"), &a).unwrap();
        let m = load(dir.path(), "m.npy", 1.0).unwrap();
        assert_eq!((m.nx, m.ny), (3, 2));
        assert_eq!(m.heights[m.nx + 2], 12.0);
    }

    #[test]
    fn unreadable_and_malformed_files_name_the_field() {
        let dir = tempfile::tempdir().unwrap();
        let e = load(dir.path(), "missing.csv", 1.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("slider.file") && e.contains("missing.csv"),
            "{e}"
        );
        std::fs::write(dir.path().join("r.csv"), "1,2\n3\n").unwrap();
        let e = load(dir.path(), "r.csv", 1.0).unwrap_err().to_string();
        assert!(e.contains("slider.file") && !e.contains('\n'), "{e}");
        std::fs::write(dir.path().join("t.csv"), "1,x\n").unwrap();
        let e = load(dir.path(), "t.csv", 1.0).unwrap_err().to_string();
        assert!(e.contains("\"x\" is not a number"), "{e}");
        let e = load(dir.path(), "m.png", 1.0).unwrap_err().to_string();
        assert!(e.contains(".csv or .npy"), "{e}");
    }
}
