//! Minimal NumPy `.npy` (format version 1.0) writer, so G-buffers and
//! visibility images can be inspected with NumPy without a serde stack.

use std::path::Path;

/// Bytes of a `.npy` file holding a little-endian f32 array of shape
/// `(height, width, 3)` in C order.
///
/// The header always describes `height * width` pixels: missing entries of
/// `data` are written as NaN and extra ones are ignored, so the file is
/// self-consistent. [`write_npy_f32_hw3`] rejects such mismatches instead.
pub fn npy_bytes_f32_hw3(width: usize, height: usize, data: &[[f32; 3]]) -> Vec<u8> {
    let dict =
        format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({height}, {width}, 3), }}");
    // Magic (6) + version (2) + header length (2), then the dict padded with
    // spaces and ended by '\n' so the data starts on a 64-byte boundary.
    let unpadded = 10 + dict.len() + 1;
    let total_header = unpadded.div_ceil(64) * 64;
    let header_len = total_header - 10;
    let pixels = width.saturating_mul(height);

    let mut out = Vec::with_capacity(total_header + pixels.saturating_mul(12));
    out.extend_from_slice(b"\x93NUMPY");
    out.extend_from_slice(&[1, 0]);
    // Version 1.0 stores the header length as u16; a shape dict is far
    // shorter than that.
    out.extend_from_slice(&(header_len as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out.resize(total_header - 1, b' ');
    out.push(b'\n');
    for i in 0..pixels {
        let px = data.get(i).copied().unwrap_or([f32::NAN; 3]);
        for v in px {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// Writes `data` (row-major, rows top to bottom) as an `(height, width, 3)`
/// f32 `.npy` file through [`crate::output::write_file`]. Refuses `data` that
/// does not hold exactly `width * height` pixels; errors name the path.
pub fn write_npy_f32_hw3(
    path: &Path,
    width: usize,
    height: usize,
    data: &[[f32; 3]],
) -> crate::Result<()> {
    if Some(data.len()) != width.checked_mul(height) {
        return Err(crate::Error::file(
            path,
            format!(
                "npy: {} pixels given for a {width}x{height} image",
                data.len()
            ),
        ));
    }
    crate::output::write_file(path, "the array", &npy_bytes_f32_hw3(width, height, data))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_is_exact() {
        let data: Vec<[f32; 3]> = (0..6).map(|i| [i as f32, 0.5, -2.0]).collect();
        let bytes = npy_bytes_f32_hw3(3, 2, &data);
        let dict = b"{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 3), }";
        assert_eq!(&bytes[..6], b"\x93NUMPY");
        assert_eq!(&bytes[6..8], &[1, 0]);
        // 10 + 62 + 1 = 73 bytes rounds up to 128, so the length field is 118.
        assert_eq!(dict.len(), 62);
        assert_eq!(u16::from_le_bytes([bytes[8], bytes[9]]), 118);
        assert_eq!(&bytes[10..72], dict);
        assert!(bytes[72..127].iter().all(|&b| b == b' '));
        assert_eq!(bytes[127], b'\n');
        assert_eq!(bytes.len(), 128 + 2 * 3 * 3 * 4);
        // First pixel of the second row, C order, little-endian.
        let at = |k: usize| {
            let o = 128 + 4 * k;
            f32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]])
        };
        assert_eq!(at(0), 0.0);
        assert_eq!(at(1), 0.5);
        assert_eq!(at(2), -2.0);
        assert_eq!(at(9), 3.0);
        assert_eq!(at(17), -2.0);
    }

    #[test]
    fn header_padding_for_larger_shapes() {
        for (w, h) in [(1280, 720), (1, 1), (100_000, 3), (0, 0)] {
            let bytes = npy_bytes_f32_hw3(w, h, &[]);
            let header = 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
            assert_eq!(header % 64, 0);
            assert_eq!(bytes[header - 1], b'\n');
            let text = String::from_utf8_lossy(&bytes[10..header]);
            assert!(
                text.contains(&format!("'shape': ({h}, {w}, 3), }}")),
                "{text}"
            );
            assert_eq!(bytes.len(), header + w * h * 12);
        }
    }

    #[test]
    fn missing_pixels_are_nan_and_writer_rejects_mismatch() {
        let bytes = npy_bytes_f32_hw3(2, 1, &[[1.0; 3]]);
        assert_eq!(bytes.len(), 128 + 24);
        let last = f32::from_le_bytes([bytes[148], bytes[149], bytes[150], bytes[151]]);
        assert!(last.is_nan());

        let dir = std::env::temp_dir();
        let path = dir.join(format!("npy_test_{}.npy", std::process::id()));
        let err = write_npy_f32_hw3(&path, 2, 2, &[[0.0; 3]; 3]);
        let text = err.map(|_| ()).unwrap_err().to_string();
        assert!(
            text.contains("npy: 3 pixels given for a 2x2 image"),
            "{text}"
        );
        assert!(!path.exists(), "a refused array writes nothing");
        let data = [[1.0, 2.0, 3.0]; 4];
        let written = write_npy_f32_hw3(&path, 2, 2, &data)
            .ok()
            .and_then(|_| std::fs::read(&path).ok());
        let _ = std::fs::remove_file(&path);
        assert_eq!(written, Some(npy_bytes_f32_hw3(2, 2, &data)));
    }
}
