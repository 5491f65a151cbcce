//! A small PNG writer for the phase portraits: an indexed-colour image (a palette of up to
//! 256 RGB colours, one byte per pixel), compressed with one fixed-Huffman deflate block whose
//! matches repeat the previous pixel or the pixel above (the portraits are mostly blank).
//! Written here instead of a raster crate: plotters' bitmap backend needs a font stack for its
//! text and an image crate for PNG, both far heavier than these hundred lines.

/// An indexed-colour raster: `pixels[y * width + x]` indexes `palette`.
#[derive(Clone, Debug)]
pub(crate) struct Raster {
    pub width: usize,
    pub height: usize,
    pub palette: Vec<[u8; 3]>,
    pub pixels: Vec<u8>,
    /// Whether colour 0 is transparent (a `tRNS` chunk).
    pub transparent: bool,
}

impl Raster {
    /// A `width x height` raster of colour 0.
    pub(crate) fn new(width: usize, height: usize, palette: Vec<[u8; 3]>) -> Self {
        Raster {
            width,
            height,
            palette,
            pixels: vec![0; width * height],
            transparent: false,
        }
    }

    /// Colour pixel `(x, y)` (`y` down) if it is inside.
    pub(crate) fn set(&mut self, x: i64, y: i64, colour: u8) {
        if (0..self.width as i64).contains(&x) && (0..self.height as i64).contains(&y) {
            self.pixels[y as usize * self.width + x as usize] = colour;
        }
    }

    /// The PNG file.
    pub(crate) fn png(&self) -> Vec<u8> {
        let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
        let mut ihdr = Vec::new();
        ihdr.extend((self.width as u32).to_be_bytes());
        ihdr.extend((self.height as u32).to_be_bytes());
        ihdr.extend([8, 3, 0, 0, 0]); // 8 bits, indexed colour
        chunk(&mut out, b"IHDR", &ihdr);
        chunk(&mut out, b"PLTE", &self.palette.concat());
        if self.transparent {
            chunk(&mut out, b"tRNS", &[0]);
        }
        let mut raw = Vec::with_capacity((self.width + 1) * self.height);
        for row in self.pixels.chunks(self.width) {
            raw.push(0); // filter: none
            raw.extend_from_slice(row);
        }
        chunk(&mut out, b"IDAT", &zlib(&raw, self.width + 1));
        chunk(&mut out, b"IEND", &[]);
        out
    }
}

fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend((data.len() as u32).to_be_bytes());
    let start = out.len();
    out.extend_from_slice(kind);
    out.extend_from_slice(data);
    let crc = crc32(&out[start..]);
    out.extend(crc.to_be_bytes());
}

/// CRC-32 (ISO 3309, the polynomial 0xEDB88320 reflected), bit by bit.
pub(crate) fn crc32(data: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

fn adler32(data: &[u8]) -> u32 {
    let (mut a, mut b) = (1u32, 0u32);
    for &x in data {
        a = (a + u32::from(x)) % 65521;
        b = (b + a) % 65521;
    }
    (b << 16) | a
}

/// Bits written least significant first, as deflate reads them.
struct Bits {
    out: Vec<u8>,
    acc: u64,
    n: u32,
}

impl Bits {
    fn put(&mut self, value: u32, count: u32) {
        self.acc |= u64::from(value) << self.n;
        self.n += count;
        while self.n >= 8 {
            self.out.push(self.acc as u8);
            self.acc >>= 8;
            self.n -= 8;
        }
    }

    /// A Huffman code, most significant bit first.
    fn code(&mut self, code: u32, len: u32) {
        let reversed = code.reverse_bits() >> (32 - len);
        self.put(reversed, len);
    }

    /// The fixed code of literal/length symbol `s`.
    fn symbol(&mut self, s: u32) {
        match s {
            0..=143 => self.code(0x30 + s, 8),
            144..=255 => self.code(0x190 + s - 144, 9),
            256..=279 => self.code(s - 256, 7),
            _ => self.code(0xC0 + s - 280, 8),
        }
    }
}

pub(crate) const LENGTH_BASE: [u32; 29] = [
    3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115, 131,
    163, 195, 227, 258,
];
pub(crate) const LENGTH_EXTRA: [u32; 29] = [
    0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0,
];
pub(crate) const DIST_BASE: [u32; 30] = [
    1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513, 769, 1025, 1537,
    2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577,
];
pub(crate) const DIST_EXTRA: [u32; 30] = [
    0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13,
    13,
];

/// The zlib stream of `data`: one final fixed-Huffman block whose matches are at distance 1
/// or `stride` (the byte above, `stride < 32768`), the longer one, greedily.
fn zlib(data: &[u8], stride: usize) -> Vec<u8> {
    let mut bits = Bits {
        out: vec![0x78, 0x01],
        acc: 0,
        n: 0,
    };
    bits.put(1, 1); // final block
    bits.put(1, 2); // fixed Huffman
    let mut i = 0;
    while i < data.len() {
        let run = |d: usize| {
            if i < d {
                return 0;
            }
            let mut l = 0;
            while l < 258 && i + l < data.len() && data[i + l] == data[i + l - d] {
                l += 1;
            }
            l
        };
        let (l1, ls) = (run(1), if stride < 32768 { run(stride) } else { 0 });
        let (len, dist) = if ls > l1 { (ls, stride) } else { (l1, 1) };
        if len < 3 {
            bits.symbol(u32::from(data[i]));
            i += 1;
            continue;
        }
        let len32 = len as u32;
        let k = LENGTH_BASE
            .iter()
            .rposition(|&b| b <= len32)
            .expect("len >= 3");
        bits.symbol(257 + k as u32);
        bits.put(len32 - LENGTH_BASE[k], LENGTH_EXTRA[k]);
        let d = dist as u32;
        let j = DIST_BASE.iter().rposition(|&b| b <= d).expect("dist >= 1");
        bits.code(j as u32, 5);
        bits.put(d - DIST_BASE[j], DIST_EXTRA[j]);
        i += len;
    }
    bits.symbol(256);
    if bits.n > 0 {
        bits.put(0, 8 - bits.n);
    }
    let mut out = bits.out;
    out.extend(adler32(data).to_be_bytes());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader of the fixed-Huffman subset the writer emits (the inverse of `zlib`).
    fn inflate_fixed(z: &[u8]) -> Vec<u8> {
        assert_eq!(&z[..2], &[0x78, 0x01]);
        let data = &z[2..z.len() - 4];
        let mut pos = 0usize;
        let mut bit = |n: u32| -> u32 {
            let mut v = 0;
            for k in 0..n {
                let b = (data[pos / 8] >> (pos % 8)) & 1;
                v |= u32::from(b) << k;
                pos += 1;
            }
            v
        };
        assert_eq!((bit(1), bit(2)), (1, 1));
        let mut out: Vec<u8> = Vec::new();
        loop {
            // Read the fixed literal/length code, MSB first.
            let mut code = 0u32;
            let mut len = 0;
            let symbol = loop {
                code = (code << 1) | bit(1);
                len += 1;
                match len {
                    7 if code <= 0x17 => break code + 256,
                    8 if (0x30..=0xBF).contains(&code) => break code - 0x30,
                    8 if (0xC0..=0xC7).contains(&code) => break code - 0xC0 + 280,
                    9 if code >= 0x190 => break code - 0x190 + 144,
                    9 => panic!("bad code"),
                    _ => {}
                }
            };
            match symbol {
                0..=255 => out.push(symbol as u8),
                256 => break,
                _ => {
                    let k = (symbol - 257) as usize;
                    let length = LENGTH_BASE[k] + bit(LENGTH_EXTRA[k]);
                    let mut j = 0;
                    for _ in 0..5 {
                        j = (j << 1) | bit(1);
                    }
                    let dist = (DIST_BASE[j as usize] + bit(DIST_EXTRA[j as usize])) as usize;
                    for _ in 0..length {
                        out.push(out[out.len() - dist]);
                    }
                }
            }
        }
        assert_eq!(adler32(&out).to_be_bytes(), z[z.len() - 4..]);
        out
    }

    #[test]
    fn deflate_round_trips_and_compresses_blank_rasters() {
        let mut data = vec![0u8; 50_000];
        for (k, x) in data.iter_mut().enumerate() {
            if k % 97 == 3 || k % 1001 < 5 {
                *x = (k % 7) as u8;
            }
        }
        let z = zlib(&data, 301);
        assert_eq!(inflate_fixed(&z), data);
        assert!(z.len() < data.len() / 5, "{}", z.len());
        // Literals of every value, both 8- and 9-bit codes.
        let all: Vec<u8> = (0..=255u8).chain((0..=255u8).rev()).collect();
        assert_eq!(inflate_fixed(&zlib(&all, 17)), all);
    }

    #[test]
    fn crc_of_the_iend_chunk() {
        // Every PNG ends with IEND and this CRC.
        assert_eq!(crc32(b"IEND"), 0xAE42_6082);
    }
}
