//! The one little-endian byte codec of the two state formats (the model's, module [`crate::state`], and the FMU's): fixed-width numbers, length-prefixed byte strings, bounds-checked reads.

/// Appends values to a byte buffer, little endian.
#[derive(Debug, Default)]
pub struct Writer(Vec<u8>);

impl Writer {
    /// An empty buffer.
    pub fn new() -> Self {
        Writer(Vec::new())
    }
    /// Room for `n` more bytes, so that writing them reallocates nothing.
    pub fn reserve(&mut self, n: usize) {
        self.0.reserve(n);
    }
    /// One byte.
    pub fn u8(&mut self, x: u8) {
        self.0.push(x);
    }
    /// A u32, 4 bytes.
    pub fn u32(&mut self, x: u32) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    /// An i32, 4 bytes.
    pub fn i32(&mut self, x: i32) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    /// An f64, 8 bytes (its bits: every value, NaN included, reads back identically).
    pub fn f64(&mut self, x: f64) {
        self.0.extend_from_slice(&x.to_le_bytes());
    }
    /// Bytes as they are (no length), e.g. a magic number.
    pub fn raw(&mut self, b: &[u8]) {
        self.0.extend_from_slice(b);
    }
    /// A byte string: u32 length, then the bytes.
    pub fn bytes(&mut self, b: &[u8]) {
        self.u32(b.len() as u32);
        self.0.extend_from_slice(b);
    }
    /// A string: u32 length, then its UTF-8 bytes.
    pub fn str(&mut self, s: &str) {
        self.bytes(s.as_bytes());
    }
    /// The bytes written.
    pub fn into_inner(self) -> Vec<u8> {
        self.0
    }
}

/// Reads values written by [`Writer`] from a byte slice; every read checks that the bytes
/// are there, so a truncated or corrupt buffer is an error with its offset, never a panic.
#[derive(Debug)]
pub struct Reader<'a> {
    d: &'a [u8],
    p: usize,
}

impl<'a> Reader<'a> {
    /// A reader at the start of `d`.
    pub fn new(d: &'a [u8]) -> Self {
        Reader { d, p: 0 }
    }
    /// The offset of the next byte.
    pub fn position(&self) -> usize {
        self.p
    }
    /// The next `n` bytes.
    pub fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let left = self.d.len() - self.p;
        if left < n {
            return Err(format!(
                "truncated at byte {} (need {n} more bytes, {left} left)",
                self.p
            ));
        }
        let s = &self.d[self.p..self.p + n];
        self.p += n;
        Ok(s)
    }
    /// One byte.
    pub fn u8(&mut self) -> Result<u8, String> {
        Ok(self.take(1)?[0])
    }
    /// A u32.
    pub fn u32(&mut self) -> Result<u32, String> {
        let b = self.take(4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    /// An i32.
    pub fn i32(&mut self) -> Result<i32, String> {
        let b = self.take(4)?;
        Ok(i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    /// An f64.
    pub fn f64(&mut self) -> Result<f64, String> {
        let b = self.take(8)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(f64::from_le_bytes(a))
    }
    /// A byte string written by [`Writer::bytes`].
    pub fn bytes(&mut self) -> Result<&'a [u8], String> {
        let n = self.u32()? as usize;
        self.take(n)
    }
    /// A string written by [`Writer::str`].
    pub fn str(&mut self) -> Result<String, String> {
        let b = self.bytes()?;
        String::from_utf8(b.to_vec()).map_err(|_| "a string is not UTF-8".to_string())
    }
    /// A boolean byte (0 or 1; anything else is an error).
    pub fn bool(&mut self) -> Result<bool, String> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(format!("bad boolean byte {b} at {}", self.p - 1)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind of value reads back bit for bit, and reading past the end is an error
    /// that names the offset, at every truncation point.
    #[test]
    fn round_trip_and_truncation() {
        let mut w = Writer::new();
        w.raw(b"MAGC");
        w.u8(7);
        w.u32(0xdead_beef);
        w.i32(-5);
        w.f64(f64::NAN);
        w.f64(-0.0);
        w.str("grüß");
        w.u8(1);
        let buf = w.into_inner();
        let read = |d: &[u8]| -> Result<(), String> {
            let mut r = Reader::new(d);
            assert_eq!(r.take(4)?, b"MAGC");
            assert_eq!(r.u8()?, 7);
            assert_eq!(r.u32()?, 0xdead_beef);
            assert_eq!(r.i32()?, -5);
            assert!(r.f64()?.is_nan());
            assert_eq!(r.f64()?.to_bits(), (-0.0f64).to_bits());
            assert_eq!(r.str()?, "grüß");
            assert!(r.bool()?);
            assert_eq!(r.position(), d.len());
            Ok(())
        };
        read(&buf).expect("whole buffer");
        for n in 0..buf.len() {
            let e = read(&buf[..n]).expect_err("truncated buffer");
            assert!(e.contains("truncated at byte"), "{n}: {e}");
        }
        let mut r = Reader::new(&[2]);
        assert!(r.bool().unwrap_err().contains("bad boolean byte 2"));
    }
}
