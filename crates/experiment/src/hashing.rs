//! The size and content hash of a shard's records file: written into its part summary as
//! the file is written, checked by `merge` before the file is read, so a file damaged or
//! swapped after its shard ended is refused.

use std::hash::Hasher;
use std::io::{Read, Write};
use std::path::Path;
use twox_hash::XxHash64;

/// A writer that passes bytes on and keeps their count and XXH64 hash: a shard's records
/// are hashed as they are written, without reading the file again.
pub struct Hashing<W> {
    inner: W,
    bytes: u64,
    hash: XxHash64,
}

impl<W: Write> Hashing<W> {
    pub fn new(inner: W) -> Self {
        Hashing {
            inner,
            bytes: 0,
            hash: XxHash64::with_seed(0),
        }
    }

    /// The bytes written and their hash, as a part records them.
    pub fn seal(&self) -> Written {
        Written {
            bytes: self.bytes,
            hash: format!("{:016x}", self.hash.finish()),
        }
    }
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.write(&buf[..n]);
        self.bytes += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// A records file's size and content hash (XXH64, seed 0, 16 hexadecimal digits).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Written {
    pub bytes: u64,
    pub hash: String,
}

/// The size and hash of a records file, read in bounded pieces; only a regular file is
/// opened (a FIFO or device named as records would block or never end) and at most
/// `expected_bytes + 1` bytes are read.
pub fn hash_file(path: &Path, expected_bytes: u64) -> Result<Written, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".to_string());
    }
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut h = Hashing::new(std::io::sink());
    std::io::copy(&mut file.take(expected_bytes.saturating_add(1)), &mut h).map_err(|e| e.to_string())?;
    Ok(h.seal())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hashed(bytes: &[u8]) -> Written {
        let mut h = Hashing::new(Vec::new());
        h.write_all(bytes).unwrap();
        assert_eq!(h.inner, bytes, "the bytes pass on unchanged");
        h.seal()
    }

    #[test]
    fn hashes_are_xxh64_of_the_bytes_written() {
        // The XXH64 test vectors (seed 0) of the reference implementation.
        assert_eq!(hashed(b"").hash, "ef46db3751d8e999");
        assert_eq!(hashed(b"abc").hash, "44bc2cf5ad770999");
        assert_eq!(hashed(b"abc").bytes, 3);
        assert_ne!(hashed(b"abc").hash, hashed(b"abd").hash);
    }

    #[test]
    fn a_file_is_hashed_as_it_was_written_and_read_no_further_than_needed() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("records.csv");
        std::fs::write(&path, b"abc").unwrap();
        assert_eq!(hash_file(&path, 3), Ok(hashed(b"abc")));
        // A file longer than the shard wrote is read one byte past: enough to say so.
        assert_eq!(hash_file(&path, 1).unwrap().bytes, 2);
        assert_eq!(hash_file(dir.path(), 3).unwrap_err(), "not a regular file");
    }
}
