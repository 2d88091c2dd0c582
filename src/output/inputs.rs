//! Outputs that would overwrite the run's own inputs (`render spec.toml --out . --format csv`
//! next to a chart named like its data file) are refused before anything is drawn.

use std::path::{Path, PathBuf};

/// An output that names one of the inputs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputClash {
    /// The output file that would be written.
    pub output: PathBuf,
    /// The input it would overwrite (as given).
    pub input: PathBuf,
}

impl std::fmt::Display for InputClash {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "output `{}` would overwrite the input `{}`, which the next run would read",
            self.output.display(),
            self.input.display()
        )
    }
}

impl std::error::Error for InputClash {}

/// The first output among `outputs` that is one of `inputs`: the same file, or the same name in
/// the same real folder (a link there that an input is read through would be replaced).
pub fn refuse_inputs(outputs: &[PathBuf], inputs: &[PathBuf]) -> Result<(), InputClash> {
    let places: Vec<(Vec<PathBuf>, &PathBuf)> = inputs.iter().map(|i| (places_of(i), i)).collect();
    for output in outputs {
        let Some(at) = in_real_folder(output) else { continue };
        if let Some((_, input)) = places.iter().find(|(p, _)| p.contains(&at)) {
            return Err(InputClash { output: output.clone(), input: (*input).clone() });
        }
    }
    Ok(())
}

/// Where an input lives: its name in its real folder and, through links, its real file.
fn places_of(input: &Path) -> Vec<PathBuf> {
    in_real_folder(input).into_iter().chain(std::fs::canonicalize(input).ok()).collect()
}

/// `path`'s file name joined to its folder's real path (the file itself may not exist yet).
fn in_real_folder(path: &Path) -> Option<PathBuf> {
    let name = path.file_name()?;
    let folder = super::folder_of(path);
    Some(std::fs::canonicalize(folder).ok()?.join(name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_file_by_another_spelling_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("data")).unwrap();
        let input = dir.path().join("data/d.csv");
        std::fs::write(&input, "x\n1\n").unwrap();
        let output = dir.path().join("data/../data/./d.csv");
        let clash = refuse_inputs(&[dir.path().join("c.svg"), output.clone()], &[input.clone()]).unwrap_err();
        assert_eq!(clash, InputClash { output, input });
        assert!(refuse_inputs(&[dir.path().join("data/d.svg")], &[dir.path().join("data/d.csv")]).is_ok());
    }

    #[cfg(unix)]
    #[test]
    fn links_either_way_are_seen_through() {
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().join("real");
        std::fs::create_dir(&real).unwrap();
        std::fs::write(real.join("d.csv"), "x\n1\n").unwrap();
        // The output folder is a link to the input's folder.
        std::os::unix::fs::symlink(&real, dir.path().join("out")).unwrap();
        assert!(refuse_inputs(&[dir.path().join("out/d.csv")], &[real.join("d.csv")]).is_err());
        // The input is read through a link that the output would replace.
        std::os::unix::fs::symlink(real.join("d.csv"), dir.path().join("link.csv")).unwrap();
        assert!(refuse_inputs(&[dir.path().join("link.csv")], &[dir.path().join("link.csv")]).is_err());
        // ... or the output names the link's target.
        assert!(refuse_inputs(&[real.join("d.csv")], &[dir.path().join("link.csv")]).is_err());
    }

    #[test]
    fn outputs_in_a_missing_folder_clash_with_nothing() {
        let dir = tempfile::tempdir().unwrap();
        assert!(refuse_inputs(&[dir.path().join("new/c.svg")], &[dir.path().join("d.csv")]).is_ok());
    }
}
