//! PC2, the point cache of Blender's Mesh Cache modifier (and 3ds Max's): a mesh's vertex
//! positions, frame after frame, in one file: a 32-byte header (`POINTCACHE2\0`, version
//! 1, the vertex count, the first frame, the frames per sample, the sample count), then
//! every sample's positions as little-endian f32 triples. It is written as the frames
//! come, so a long run never holds more than one in memory, and read back for tests and
//! tools.

use crate::error::FormatError;
use std::fs::File;
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

const SIGNATURE: &[u8; 12] = b"POINTCACHE2\0";
const HEADER_BYTES: usize = 32;
/// Where the header keeps the sample count, written last.
const SAMPLES_AT: u64 = 28;

/// A PC2 file being written: frames are appended to `path.tmp`, which [`Pc2Writer::finish`]
/// completes and renames to `path` (dropped unfinished, it finishes what it has).
#[derive(Debug)]
pub struct Pc2Writer {
    path: PathBuf,
    tmp: PathBuf,
    out: Option<BufWriter<File>>,
    points: usize,
    samples: u32,
}

impl Pc2Writer {
    /// Starts a cache of `points` vertices; its first sample is at frame `start_frame`,
    /// and samples are `sample_rate` frames apart.
    pub fn create(path: &Path, points: usize, start_frame: f32, sample_rate: f32) -> std::io::Result<Self> {
        let count = u32::try_from(points).map_err(|_| {
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "too many vertices for PC2")
        })?;
        let mut tmp = path.as_os_str().to_owned();
        tmp.push(".tmp");
        let tmp = PathBuf::from(tmp);
        let mut out = BufWriter::new(File::create(&tmp)?);
        out.write_all(SIGNATURE)?;
        out.write_all(&1u32.to_le_bytes())?;
        out.write_all(&count.to_le_bytes())?;
        out.write_all(&start_frame.to_le_bytes())?;
        out.write_all(&sample_rate.to_le_bytes())?;
        out.write_all(&0u32.to_le_bytes())?;
        Ok(Self {
            path: path.to_path_buf(),
            tmp,
            out: Some(out),
            points,
            samples: 0,
        })
    }

    /// Appends one sample: every vertex's position, in the mesh's order.
    pub fn push(&mut self, positions: &[[f32; 3]]) -> std::io::Result<()> {
        if positions.len() != self.points {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "a sample of {} vertices in a cache of {}",
                    positions.len(),
                    self.points
                ),
            ));
        }
        let out = self
            .out
            .as_mut()
            .ok_or_else(|| std::io::Error::other("the cache is finished"))?;
        for p in positions {
            for c in p {
                out.write_all(&c.to_le_bytes())?;
            }
        }
        self.samples += 1;
        Ok(())
    }

    /// Samples written so far.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// Writes the sample count into the header and puts the file in place.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.close()
    }

    fn close(&mut self) -> std::io::Result<()> {
        let Some(out) = self.out.take() else {
            return Ok(());
        };
        let mut file = out.into_inner().map_err(|e| e.into_error())?;
        file.seek(SeekFrom::Start(SAMPLES_AT))?;
        file.write_all(&self.samples.to_le_bytes())?;
        file.sync_all()?;
        std::fs::rename(&self.tmp, &self.path)
    }
}

impl Drop for Pc2Writer {
    fn drop(&mut self) {
        if self.close().is_err() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// A PC2 file open for reading one sample at a time, so a long cache need not fit in
/// memory.
#[derive(Debug)]
pub struct Pc2Reader {
    path: PathBuf,
    file: File,
    pub points: usize,
    pub start_frame: f32,
    pub sample_rate: f32,
    pub samples: usize,
}

impl Pc2Reader {
    /// Reads and checks the header: the file must hold exactly the samples it announces.
    pub fn open(path: &Path) -> Result<Self, FormatError> {
        let io = |source| FormatError::Io {
            path: path.to_path_buf(),
            source,
        };
        let parse = |message: String| FormatError::Parse {
            path: path.to_path_buf(),
            line: None,
            message,
        };
        let mut file = File::open(path).map_err(io)?;
        let length = file.metadata().map_err(io)?.len();
        let mut header = [0u8; HEADER_BYTES];
        if length < HEADER_BYTES as u64 || file.read_exact(&mut header).is_err() || &header[..12] != SIGNATURE
        {
            return Err(parse("not a PC2 file: no POINTCACHE2 header".into()));
        }
        let word = |at: usize| <[u8; 4]>::try_from(&header[at..at + 4]).expect("4 bytes");
        let version = u32::from_le_bytes(word(12));
        if version != 1 {
            return Err(parse(format!("PC2 version {version}; only 1 is known")));
        }
        let points = u32::from_le_bytes(word(16)) as u64;
        let samples = u32::from_le_bytes(word(28)) as u64;
        if HEADER_BYTES as u64 + 12 * points * samples != length {
            return Err(parse(format!(
                "{samples} samples of {points} vertices do not fill the file's {length} bytes"
            )));
        }
        Ok(Self {
            path: path.to_path_buf(),
            file,
            points: points as usize,
            start_frame: f32::from_le_bytes(word(20)),
            sample_rate: f32::from_le_bytes(word(24)),
            samples: samples as usize,
        })
    }

    /// Sample `k`'s positions.
    pub fn sample(&mut self, k: usize) -> Result<Vec<[f32; 3]>, FormatError> {
        if k >= self.samples {
            return Err(FormatError::Parse {
                path: self.path.clone(),
                line: None,
                message: format!("no sample {k} in a cache of {}", self.samples),
            });
        }
        let mut bytes = vec![0u8; 12 * self.points];
        let at = HEADER_BYTES as u64 + (k * bytes.len()) as u64;
        self.file
            .seek(SeekFrom::Start(at))
            .and_then(|_| self.file.read_exact(&mut bytes))
            .map_err(|source| FormatError::Io {
                path: self.path.clone(),
                source,
            })?;
        let float = |b: &[u8]| f32::from_le_bytes(b.try_into().expect("4 bytes"));
        Ok(bytes
            .chunks_exact(12)
            .map(|p| [float(&p[0..4]), float(&p[4..8]), float(&p[8..12])])
            .collect())
    }
}

/// A PC2 file read back whole.
#[derive(Debug, Clone, PartialEq)]
pub struct Pc2 {
    pub start_frame: f32,
    pub sample_rate: f32,
    /// Every sample's positions.
    pub samples: Vec<Vec<[f32; 3]>>,
}

impl Pc2 {
    pub fn read(path: &Path) -> Result<Self, FormatError> {
        let mut reader = Pc2Reader::open(path)?;
        let samples = (0..reader.samples)
            .map(|k| reader.sample(k))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            start_frame: reader.start_frame,
            sample_rate: reader.sample_rate,
            samples,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_written_cache_reads_back() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cloth.pc2");
        let mut cache = Pc2Writer::create(&path, 2, 1.0, 0.5).unwrap();
        cache.push(&[[0.0, 1.0, 2.0], [3.0, 4.0, 5.5]]).unwrap();
        cache.push(&[[0.5, 1.0, 2.0], [3.0, -4.0, 5.5]]).unwrap();
        assert!(cache.push(&[[0.0; 3]]).is_err(), "a sample of the wrong size");
        assert_eq!(cache.samples(), 2);
        assert!(!path.exists(), "in place only when finished");
        cache.finish().unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(bytes.len(), 32 + 2 * 2 * 12);
        assert_eq!(&bytes[..12], b"POINTCACHE2\0");
        let read = Pc2::read(&path).unwrap();
        assert_eq!(read.start_frame, 1.0);
        assert_eq!(read.sample_rate, 0.5);
        assert_eq!(
            read.samples,
            vec![
                vec![[0.0, 1.0, 2.0], [3.0, 4.0, 5.5]],
                vec![[0.5, 1.0, 2.0], [3.0, -4.0, 5.5]]
            ]
        );
    }

    #[test]
    fn a_cache_dropped_unfinished_keeps_its_samples() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cut.pc2");
        let mut cache = Pc2Writer::create(&path, 1, 0.0, 1.0).unwrap();
        cache.push(&[[1.0, 2.0, 3.0]]).unwrap();
        drop(cache);
        assert_eq!(Pc2::read(&path).unwrap().samples, vec![vec![[1.0, 2.0, 3.0]]]);
    }

    #[test]
    fn a_short_file_is_refused_saying_why() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("short.pc2");
        let mut bytes = b"POINTCACHE2\0".to_vec();
        for w in [1u32, 5, 0, 0, 3] {
            bytes.extend(w.to_le_bytes());
        }
        std::fs::write(&path, &bytes).unwrap();
        let e = Pc2::read(&path).unwrap_err().to_string();
        assert!(
            e.contains("short.pc2") && e.contains("3 samples of 5 vertices"),
            "{e}"
        );
    }
}
