//! Loading an input file into memory, for the readers (which take text already in memory).

use std::fs::{self, File};
use std::io::{self, Read, Seek, SeekFrom};
use std::path::Path;

/// From this size on, a file is read by two threads, a half each: copying from the page cache
/// into fresh memory costs a page fault per page, which the two cores then share.
const PARALLEL_READ_BYTES: u64 = 8 << 20;

/// Reads a whole file as text; invalid UTF-8 (in a comment, say) becomes U+FFFD.
pub fn read_text_file(path: &Path) -> io::Result<String> {
    let bytes = read_file(path)?;
    Ok(match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    })
}

/// Reads a whole file: a large one on two threads when there are two cores.
pub fn read_file(path: &Path) -> io::Result<Vec<u8>> {
    use std::os::unix::fs::FileExt;
    let mut file = File::open(path)?;
    let length = file.metadata()?.len();
    let two_cores = crate::threads::two_cores();
    let size = match usize::try_from(length) {
        Ok(size) if length >= PARALLEL_READ_BYTES && two_cores => size,
        _ => return fs::read(path),
    };
    let mut bytes = vec![0u8; size];
    let (first, second) = bytes.split_at_mut(size / 2);
    let offset = first.len() as u64;
    std::thread::scope(|scope| {
        let reader = &file;
        let second_half = scope.spawn(move || reader.read_exact_at(second, offset));
        reader.read_exact_at(first, 0)?;
        second_half
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })?;
    // The file may have grown since its length was taken: read on to its end.
    file.seek(SeekFrom::Start(length))?;
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_and_small_files_read_whole() {
        let dir = std::env::temp_dir().join(format!("triangle-rs-load-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        for size in [0usize, 1, 4097, PARALLEL_READ_BYTES as usize + 12_345] {
            let bytes: Vec<u8> = (0..size).map(|i| (i * 7 + i / 4099) as u8).collect();
            let path = dir.join(format!("f{size}"));
            fs::write(&path, &bytes).unwrap();
            assert!(read_file(&path).unwrap() == bytes, "{size} bytes");
        }
        fs::write(dir.join("text"), b"1 2\n# caf\xe9\n").unwrap();
        assert_eq!(
            read_text_file(&dir.join("text")).unwrap(),
            "1 2\n# caf\u{fffd}\n"
        );
        assert!(read_file(&dir.join("missing")).is_err());
        fs::remove_dir_all(&dir).unwrap();
    }
}
