//! The one EXR writer: the header and an empty offset table first, then blocks of rows as
//! they become available, then the offset table. A render hands it each strip as the strip is
//! finished, so memory is two strips' blocks whatever the image size; `merge` and `relight`
//! hand it a whole image. The bytes are the same for any number of threads, because blocks
//! are written in order, and the same however the rows arrive.
//!
//! Blocks are compressed in the background, as jobs on the render's threads: a strip's
//! blocks are still compressing while the next strip renders, so that no core waits idle
//! through the last block of a strip.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufWriter, Cursor, Seek, SeekFrom, Write};
use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::time::{Duration, Instant};

use exr::meta::header::Header;
use exr::meta::{MetaData, Requirements};
use rayon::prelude::*;

use crate::output::exr_block;
use crate::output::exr_header;

/// A compressed block, or why it could not be, by block index.
type Compressed = (usize, Result<Vec<u8>, String>);

/// An EXR being written block by block.
pub struct ExrStream<'f> {
    out: BufWriter<&'f mut File>,
    header: Arc<Header>,
    /// Where the offset table starts, and the file position of every block written so far.
    table: u64,
    offsets: Vec<u64>,
    position: u64,
    /// Lines per block, by codec.
    lines: u32,
    /// Blocks handed to compression so far; those from `offsets.len()` on are not written.
    submitted: usize,
    /// Compression jobs report here; finished blocks wait in `ready` until all before them
    /// are written.
    sender: Sender<Compressed>,
    done: Receiver<Compressed>,
    ready: BTreeMap<usize, Vec<u8>>,
    /// Nanoseconds spent packing, compressing and writing, summed over threads.
    work: Arc<AtomicU64>,
}

impl<'f> ExrStream<'f> {
    /// Writes `header` (a single-part scanline image), its attributes in name order so that
    /// equal images give equal bytes, and room for the offset table.
    pub fn create(file: &'f mut File, header: Header) -> Result<Self, String> {
        let requirements =
            MetaData::validate(std::slice::from_ref(&header), true).map_err(|e| e.to_string())?;
        let mut bytes = Cursor::new(Vec::new());
        write_magic_and_header(&mut bytes, requirements, &header)?;
        exr_header::sort_attributes(&mut bytes).map_err(|e| e.to_string())?;
        let mut bytes = bytes.into_inner();
        let table = bytes.len() as u64;
        bytes.resize(bytes.len() + header.chunk_count * 8, 0);
        let mut out = BufWriter::with_capacity(1 << 20, file);
        out.write_all(&bytes).map_err(|e| e.to_string())?;
        let (sender, done) = channel();
        Ok(ExrStream {
            out,
            lines: header.compression.scan_lines_per_block() as u32,
            offsets: Vec::with_capacity(header.chunk_count),
            header: Arc::new(header),
            table,
            position: bytes.len() as u64,
            submitted: 0,
            sender,
            done,
            ready: BTreeMap::new(),
            work: Arc::default(),
        })
    }

    /// Packs the next `rows` rows of the image and starts compressing them; `pack` gives rows
    /// (counted from the first of these) in OpenEXR's uncompressed block layout. Returns once
    /// every block of earlier calls is written, so that at most two calls' blocks are held.
    pub fn write_rows(
        &mut self,
        rows: u32,
        pack: &(dyn Fn(Range<u32>) -> Vec<u8> + Sync),
    ) -> Result<(), String> {
        let first_line = self.submitted * self.lines as usize;
        let lines = self.lines;
        let work = &self.work;
        let packed: Vec<(usize, usize, Vec<u8>)> = (0..rows)
            .step_by(lines as usize)
            .collect::<Vec<u32>>()
            .into_par_iter()
            .map(|first| {
                let started = Instant::now();
                let last = (first + lines).min(rows);
                let block = pack(first..last);
                add_time(work, started);
                (first_line + first as usize, (last - first) as usize, block)
            })
            .collect();
        let new_blocks = packed.len();
        for (line, count, block) in packed {
            let (index, header) = (self.submitted, Arc::clone(&self.header));
            let (sender, work) = (self.sender.clone(), Arc::clone(&self.work));
            rayon::spawn(move || {
                let started = Instant::now();
                let compressed = exr_block::compress(block, &header, line, count);
                add_time(&work, started);
                // No receiver means the file was abandoned (an earlier error): nothing to do.
                let _ = sender.send((index, compressed));
            });
            self.submitted += 1;
        }
        self.write_ready(new_blocks)
    }

    /// Writes compressed blocks in order as they arrive, until at most `unwritten` submitted
    /// blocks are left; waiting threads run pending jobs (compression, rendering) meanwhile.
    fn write_ready(&mut self, unwritten: usize) -> Result<(), String> {
        loop {
            while let Ok((index, compressed)) = self.done.try_recv() {
                self.ready.insert(index, compressed?);
            }
            while let Some(block) = self.ready.remove(&self.offsets.len()) {
                let started = Instant::now();
                self.write_block(block)?;
                add_time(&self.work, started);
            }
            if self.submitted - self.offsets.len() <= unwritten {
                return Ok(());
            }
            if rayon::yield_now() != Some(rayon::Yield::Executed) {
                // Nothing to run here: the blocks are compressing on other threads.
                let (index, compressed) = self
                    .done
                    .recv()
                    .map_err(|_| "an EXR compression job was lost".to_string())?;
                self.ready.insert(index, compressed?);
            }
        }
    }

    /// Appends the next block: its first line, its size, its bytes.
    fn write_block(&mut self, data: Vec<u8>) -> Result<(), String> {
        let top = self.header.own_attributes.layer_position.y();
        let line = self.offsets.len() * self.lines as usize;
        let y = i64::from(top) + line as i64;
        let y = i32::try_from(y).map_err(|_| "an EXR line beyond 2^31")?;
        let size = i32::try_from(data.len()).map_err(|_| "an EXR block over 2 GiB")?;
        self.offsets.push(self.position);
        let write = |out: &mut BufWriter<&mut File>| -> std::io::Result<()> {
            out.write_all(&y.to_le_bytes())?;
            out.write_all(&size.to_le_bytes())?;
            out.write_all(&data)
        };
        write(&mut self.out).map_err(|e| e.to_string())?;
        self.position += 8 + data.len() as u64;
        Ok(())
    }

    /// Writes the last blocks and fills in the offset table. Returns the time spent on the
    /// file's blocks: packing, compressing and writing, summed over threads.
    pub fn finish(mut self) -> Result<Duration, String> {
        let started = Instant::now();
        self.write_ready(0)?;
        if self.offsets.len() != self.header.chunk_count {
            return Err(format!(
                "{} of {} EXR blocks were written",
                self.offsets.len(),
                self.header.chunk_count
            ));
        }
        let table: Vec<u8> = self.offsets.iter().flat_map(|o| o.to_le_bytes()).collect();
        let mut finish = || -> std::io::Result<()> {
            self.out.seek(SeekFrom::Start(self.table))?;
            self.out.write_all(&table)?;
            self.out.flush()
        };
        finish().map_err(|e| e.to_string())?;
        add_time(&self.work, started);
        Ok(Duration::from_nanos(self.work.load(Ordering::Relaxed)))
    }
}

fn add_time(total: &AtomicU64, started: Instant) {
    let nanos = u64::try_from(started.elapsed().as_nanos()).unwrap_or(u64::MAX);
    total.fetch_add(nanos, Ordering::Relaxed);
}

/// The magic number, version field and `header` of a single-part file.
fn write_magic_and_header(
    out: &mut impl std::io::Write,
    requirements: Requirements,
    header: &Header,
) -> Result<(), String> {
    let mut write = || -> exr::error::UnitResult {
        exr::meta::magic_number::write(out)?;
        requirements.write(out)?;
        Header::write_all(std::slice::from_ref(header), out, false)
    };
    write().map_err(|e| e.to_string())
}
