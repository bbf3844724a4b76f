//! The one EXR writer: the header and an empty offset table first, then blocks of rows as
//! they become available (compressed on every core), then the offset table. A render hands
//! it each strip as the strip is finished, so memory is a strip's blocks whatever the image
//! size; `merge` and `relight` hand it a whole image. The bytes are the same for any number of
//! threads, because blocks are written in order, and the same however the rows arrive.

use std::fs::File;
use std::io::{BufWriter, Cursor, Seek, SeekFrom, Write};
use std::ops::Range;

use exr::meta::header::Header;
use exr::meta::{MetaData, Requirements};
use rayon::prelude::*;

use crate::output::exr_block;
use crate::output::exr_header;

/// An EXR being written block by block.
pub struct ExrStream<'f> {
    out: BufWriter<&'f mut File>,
    header: Header,
    /// Where the offset table starts, and the file position of every block written so far.
    table: u64,
    offsets: Vec<u64>,
    position: u64,
    /// Lines per block, by codec.
    lines: u32,
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
        Ok(ExrStream {
            out,
            lines: header.compression.scan_lines_per_block() as u32,
            offsets: Vec::with_capacity(header.chunk_count),
            header,
            table,
            position: bytes.len() as u64,
        })
    }

    /// Lines per block: every call to `write_rows` but the last must be a multiple of it.
    pub fn lines_per_block(&self) -> u32 {
        self.lines
    }

    /// Compresses and writes the next `rows` rows of the image; `pack` gives rows (counted
    /// from the first of these) in OpenEXR's uncompressed block layout.
    pub fn write_rows(
        &mut self,
        rows: u32,
        pack: &(dyn Fn(Range<u32>) -> Vec<u8> + Sync),
    ) -> Result<(), String> {
        let done_lines = self.offsets.len() * self.lines as usize;
        let blocks: Vec<u32> = (0..rows).step_by(self.lines as usize).collect();
        let (header, lines) = (&self.header, self.lines);
        let compressed: Vec<Result<Vec<u8>, String>> = blocks
            .par_iter()
            .map(|&first| {
                let last = (first + lines).min(rows);
                let line = done_lines + first as usize;
                exr_block::compress(pack(first..last), header, line, (last - first) as usize)
            })
            .collect();
        let top = self.header.own_attributes.layer_position.y();
        for (first, data) in blocks.into_iter().zip(compressed) {
            let data = data?;
            let y = i64::from(top) + (done_lines + first as usize) as i64;
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
        }
        Ok(())
    }

    /// Fills in the offset table once every block is written.
    pub fn finish(mut self) -> Result<(), String> {
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
        finish().map_err(|e| e.to_string())
    }
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
