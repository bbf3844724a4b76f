//! Puts the attributes of a written single-part OpenEXR header in name order.
//!
//! The `exr` crate keeps custom attributes in a `HashMap` and writes them in its iteration
//! order, which changes from one process to the next, so two identical renders would differ
//! in their header bytes. OpenEXR's own library keeps a header as a map sorted by name; we
//! rewrite ours the same way. Only the order changes, so the header keeps its length and the
//! offset table after it stays valid.

use std::io::{self, Read, Seek, SeekFrom, Write};

use crate::openexr::MAGIC;

/// Version-field flag: the file has several parts (we only write one).
const MULTIPART: u32 = 0x1000;

/// One attribute exactly as stored: name, type name and value bytes.
struct RawAttribute {
    name: Vec<u8>,
    bytes: Vec<u8>,
}

/// Reorders the header attributes of the single-part EXR in `file` by name, in place.
pub fn sort_attributes(file: &mut (impl Read + Write + Seek)) -> io::Result<()> {
    file.seek(SeekFrom::Start(0))?;
    let mut prefix = [0u8; 8];
    file.read_exact(&mut prefix)?;
    let version = u32::from_le_bytes([prefix[4], prefix[5], prefix[6], prefix[7]]);
    if prefix[..4] != MAGIC || version & MULTIPART != 0 {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            "not a single-part OpenEXR file",
        ));
    }
    let mut reader = io::BufReader::new(&mut *file);
    let mut attributes = Vec::new();
    loop {
        let name = read_null_terminated(&mut reader)?;
        if name.is_empty() {
            break;
        }
        let type_name = read_null_terminated(&mut reader)?;
        let mut size = [0u8; 4];
        reader.read_exact(&mut size)?;
        let len = usize::try_from(i32::from_le_bytes(size))
            .map_err(|_| io::Error::new(io::ErrorKind::InvalidData, "negative attribute size"))?;
        let mut value = vec![0; len];
        reader.read_exact(&mut value)?;
        let mut bytes = Vec::with_capacity(name.len() + type_name.len() + 6 + len);
        for part in [&name, &type_name] {
            bytes.extend_from_slice(part);
            bytes.push(0);
        }
        bytes.extend_from_slice(&size);
        bytes.extend_from_slice(&value);
        attributes.push(RawAttribute { name, bytes });
    }
    drop(reader);
    attributes.sort_by(|a, b| a.name.cmp(&b.name));
    file.seek(SeekFrom::Start(8))?;
    for attribute in &attributes {
        file.write_all(&attribute.bytes)?;
    }
    file.flush()
}

fn read_null_terminated(reader: &mut impl io::BufRead) -> io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    reader.read_until(0, &mut bytes)?;
    if bytes.pop() != Some(0) {
        return Err(io::Error::new(
            io::ErrorKind::UnexpectedEof,
            "truncated OpenEXR header",
        ));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn attribute(name: &str, ty: &str, value: &[u8]) -> Vec<u8> {
        let mut b = Vec::new();
        b.extend_from_slice(name.as_bytes());
        b.push(0);
        b.extend_from_slice(ty.as_bytes());
        b.push(0);
        b.extend_from_slice(&(value.len() as i32).to_le_bytes());
        b.extend_from_slice(value);
        b
    }

    #[test]
    fn sorts_by_name_and_keeps_everything_else() {
        let mut file = MAGIC.to_vec();
        file.extend_from_slice(&2u32.to_le_bytes());
        file.extend(attribute("zeta", "int", &7i32.to_le_bytes()));
        file.extend(attribute("alpha", "string", b"hello"));
        file.extend(attribute("mid", "float", &1.5f32.to_le_bytes()));
        file.push(0);
        file.extend_from_slice(b"offsets and pixels");
        let mut expected = file[..8].to_vec();
        expected.extend(attribute("alpha", "string", b"hello"));
        expected.extend(attribute("mid", "float", &1.5f32.to_le_bytes()));
        expected.extend(attribute("zeta", "int", &7i32.to_le_bytes()));
        expected.push(0);
        expected.extend_from_slice(b"offsets and pixels");

        let mut cursor = io::Cursor::new(file);
        sort_attributes(&mut cursor).expect("sorted");
        assert_eq!(cursor.into_inner(), expected);
    }

    #[test]
    fn refuses_other_files() {
        let mut cursor = io::Cursor::new(b"\x89PNG\r\n\x1a\n....".to_vec());
        assert!(sort_attributes(&mut cursor).is_err());
        let mut truncated = MAGIC.to_vec();
        truncated.extend_from_slice(&2u32.to_le_bytes());
        truncated.extend_from_slice(b"name");
        assert!(sort_attributes(&mut io::Cursor::new(truncated)).is_err());
    }
}
