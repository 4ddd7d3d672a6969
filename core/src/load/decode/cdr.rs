//! A cursor over OMG CDR (XCDR1) as ROS 2 writes it: a 4-byte encapsulation
//! header selects the byte order, and every primitive is aligned to its own
//! size counted from the end of that header.

/// Reads primitives from one CDR-encoded message.
pub struct CdrReader<'a> {
    body: &'a [u8],
    pos: usize,
    little_endian: bool,
}

impl<'a> CdrReader<'a> {
    /// Starts reading after the encapsulation header (`00 00` big-endian CDR,
    /// `00 01` little-endian CDR; the options bytes are ignored).
    pub fn new(message: &'a [u8]) -> Result<Self, String> {
        let Some((header, body)) = message.split_at_checked(4) else {
            return Err(format!(
                "{} bytes is shorter than the CDR encapsulation header",
                message.len()
            ));
        };
        let little_endian = match (header[0], header[1]) {
            (0x00, 0x00) => false,
            (0x00, 0x01) => true,
            (a, b) => {
                return Err(format!(
                    "unsupported CDR encapsulation {a:02x} {b:02x} (expected plain CDR)"
                ));
            }
        };
        Ok(Self {
            body,
            pos: 0,
            little_endian,
        })
    }

    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N], String> {
        let aligned = self.pos.next_multiple_of(N);
        let bytes = self
            .body
            .get(aligned..aligned + N)
            .ok_or_else(|| format!("message ends before {what} (offset {})", aligned + 4))?;
        self.pos = aligned + N;
        let mut out = [0; N];
        out.copy_from_slice(bytes);
        Ok(out)
    }

    /// A 32-bit signed integer.
    pub fn i32(&mut self, what: &str) -> Result<i32, String> {
        let b = self.take::<4>(what)?;
        Ok(if self.little_endian {
            i32::from_le_bytes(b)
        } else {
            i32::from_be_bytes(b)
        })
    }

    /// A 32-bit unsigned integer.
    pub fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.take::<4>(what)?;
        Ok(if self.little_endian {
            u32::from_le_bytes(b)
        } else {
            u32::from_be_bytes(b)
        })
    }

    /// A 64-bit float.
    pub fn f64(&mut self, what: &str) -> Result<f64, String> {
        let b = self.take::<8>(what)?;
        Ok(if self.little_endian {
            f64::from_le_bytes(b)
        } else {
            f64::from_be_bytes(b)
        })
    }

    /// A string: a u32 length that counts the terminating NUL, then the bytes.
    pub fn string(&mut self, what: &str) -> Result<&'a str, String> {
        let len = self.u32(what)? as usize;
        let bytes = self
            .body
            .get(self.pos..self.pos.saturating_add(len))
            .ok_or_else(|| format!("{what}: string length {len} runs past the message"))?;
        self.pos += len;
        let text = bytes.strip_suffix(&[0]).unwrap_or(bytes);
        std::str::from_utf8(text).map_err(|e| format!("{what}: not UTF-8: {e}"))
    }
}

/// Writes primitives as little-endian CDR, the inverse of [`CdrReader`].
pub struct CdrWriter {
    buf: Vec<u8>,
}

impl Default for CdrWriter {
    fn default() -> Self {
        Self::new()
    }
}

impl CdrWriter {
    /// An empty message with the little-endian CDR header.
    pub fn new() -> Self {
        Self {
            buf: vec![0x00, 0x01, 0x00, 0x00],
        }
    }

    fn align(&mut self, n: usize) {
        let body_len = self.buf.len() - 4;
        self.buf.resize(4 + body_len.next_multiple_of(n), 0);
    }

    /// A 32-bit signed integer.
    pub fn i32(&mut self, v: i32) {
        self.align(4);
        self.buf.extend_from_slice(&v.to_le_bytes());
    }

    /// A 32-bit unsigned integer.
    pub fn u32(&mut self, v: u32) {
        self.align(4);
        self.buf.extend_from_slice(&v.to_le_bytes());
    }

    /// A 64-bit float.
    pub fn f64(&mut self, v: f64) {
        self.align(8);
        self.buf.extend_from_slice(&v.to_le_bytes());
    }

    /// A string with its NUL terminator.
    pub fn string(&mut self, s: &str) {
        self.u32(s.len() as u32 + 1);
        self.buf.extend_from_slice(s.as_bytes());
        self.buf.push(0);
    }

    /// The finished message.
    pub fn finish(self) -> Vec<u8> {
        self.buf
    }
}
