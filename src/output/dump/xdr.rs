//! XDR encoding of XTC frames: big-endian integers and floats, and the compressed 3D
//! coordinates of GROMACS (F. van Hoesel's `xdr3dfcoord`, as LAMMPS's dump_xtc.cpp has
//! it), ported operation for operation so the bytes are LAMMPS's: coordinates rounded to
//! integers at a precision, their range's bit width, and runs of small differences
//! between neighbours packed into mixed-radix integers of a changing size.

/// Sizes of the small differences, by index (`magicints` of xdrfile).
const MAGICINTS: [i32; 73] = [
    0, 0, 0, 0, 0, 0, 0, 0, 0, 8, 10, 12, 16, 20, 25, 32, 40, 50, 64, 80, 101, 128, 161, 203, 256, 322, 406, 512, 645, 812, 1024, 1290, 1625, 2048, 2580,
    3250, 4096, 5060, 6501, 8192, 10321, 13003, 16384, 20642, 26007, 32768, 41285, 52015, 65536, 82570, 104031, 131072, 165140, 208063, 262144, 330280,
    416127, 524287, 660561, 832255, 1048576, 1321122, 1664510, 2097152, 2642245, 3329021, 4194304, 5284491, 6658042, 8388607, 10568983, 13316085, 16777216,
];
const FIRSTIDX: usize = 9;
const LASTIDX: usize = MAGICINTS.len() - 1;
/// The largest scaled coordinate that fits an int.
const MAXABS: f32 = (i32::MAX - 2) as f32;

pub fn int(o: &mut Vec<u8>, i: i32) {
    o.extend_from_slice(&i.to_be_bytes());
}

pub fn float(o: &mut Vec<u8>, f: f32) {
    o.extend_from_slice(&f.to_be_bytes());
}

/// A bit stream: whole bytes, and the bits of the one being filled (`sendbits`' state).
#[derive(Default)]
struct Bits {
    bytes: Vec<u8>,
    lastbits: u32,
    lastbyte: u32,
}

impl Bits {
    /// Appends the low `n` bits of `num` (`sendbits`).
    fn send(&mut self, mut n: u32, num: u32) {
        while n >= 8 {
            self.lastbyte = (self.lastbyte << 8) | (num >> (n - 8));
            self.bytes.push((self.lastbyte >> self.lastbits) as u8);
            n -= 8;
        }
        if n > 0 {
            self.lastbyte = (self.lastbyte << n) | num;
            self.lastbits += n;
            if self.lastbits >= 8 {
                self.lastbits -= 8;
                self.bytes.push((self.lastbyte >> self.lastbits) as u8);
            }
        }
    }

    /// Three integers below `sizes` as one mixed-radix number of `nbits` bits (`sendints`).
    fn send_ints(&mut self, nbits: u32, sizes: [u32; 3], nums: [u32; 3]) {
        let mut bytes = [0u32; 32];
        let mut nbytes = 0;
        let mut tmp = nums[0];
        loop {
            bytes[nbytes] = tmp & 0xff;
            nbytes += 1;
            tmp >>= 8;
            if tmp == 0 {
                break;
            }
        }
        for i in 1..3 {
            nbytes = mul_add(&mut bytes, nbytes, sizes[i], nums[i]);
        }
        if nbits >= nbytes as u32 * 8 {
            for &b in &bytes[..nbytes] {
                self.send(8, b);
            }
            self.send(nbits - nbytes as u32 * 8, 0);
        } else {
            for &b in &bytes[..nbytes - 1] {
                self.send(8, b);
            }
            self.send(nbits - (nbytes as u32 - 1) * 8, bytes[nbytes - 1]);
        }
    }

    /// The bytes with the partial last one (its bits at the top).
    fn finish(mut self) -> Vec<u8> {
        if self.lastbits > 0 {
            self.bytes.push((self.lastbyte << (8 - self.lastbits)) as u8);
        }
        self.bytes
    }
}

/// The little-endian base-256 number in `bytes[..n]` times `size` plus `add`; returns its
/// byte count.
fn mul_add(bytes: &mut [u32; 32], n: usize, size: u32, add: u32) -> usize {
    let (mut tmp, mut k) = (add, 0);
    while k < n {
        tmp = bytes[k].wrapping_mul(size).wrapping_add(tmp);
        bytes[k] = tmp & 0xff;
        tmp >>= 8;
        k += 1;
    }
    while tmp != 0 {
        bytes[k] = tmp & 0xff;
        k += 1;
        tmp >>= 8;
    }
    k
}

/// The bits of an integer below `size` (`sizeofint`).
fn bits_of_int(size: i32) -> u32 {
    let (mut num, mut bits) = (1u32, 0);
    while size >= num as i32 && bits < 32 {
        bits += 1;
        num <<= 1;
    }
    bits
}

/// The bits of a mixed-radix number of digits below `sizes` (`sizeofints`).
fn bits_of_ints(sizes: [u32; 3]) -> u32 {
    let mut bytes = [0u32; 32];
    bytes[0] = 1;
    let mut nbytes = 1;
    for s in sizes {
        nbytes = mul_add(&mut bytes, nbytes, s, 0);
    }
    let (mut num, mut bits) = (1u32, 0);
    nbytes -= 1;
    while bytes[nbytes] >= num {
        bits += 1;
        num *= 2;
    }
    bits + nbytes as u32 * 8
}

/// Appends the coordinates `xyz` (x, y, z per particle) compressed at `precision`
/// (`xdr3dfcoord` writing); false when a scaled coordinate overflows an int (the frame
/// is written anyway, as LAMMPS does).
pub fn coords(o: &mut Vec<u8>, xyz: &[f32], precision: f32) -> bool {
    let size = xyz.len() / 3;
    int(o, size as i32);
    if size <= 9 {
        xyz.iter().for_each(|&f| float(o, f));
        return true;
    }
    float(o, precision);
    let mut ok = true;
    let (mut minint, mut maxint) = ([i32::MAX; 3], [i32::MIN; 3]);
    let mut mindiff = i32::MAX;
    let mut old = [0i32; 3];
    let mut ip: Vec<i32> = Vec::with_capacity(xyz.len());
    for (n, p) in xyz.chunks_exact(3).enumerate() {
        let mut l = [0i32; 3];
        for k in 0..3 {
            let scaled = p[k] * precision;
            let lf = if p[k] >= 0.0 { (f64::from(scaled) + 0.5) as f32 } else { (f64::from(scaled) - 0.5) as f32 };
            if lf.abs() > MAXABS {
                ok = false;
            }
            l[k] = lf as i32;
            minint[k] = minint[k].min(l[k]);
            maxint[k] = maxint[k].max(l[k]);
        }
        ip.extend_from_slice(&l);
        let diff = (0..3).fold(0i32, |d, k| d.wrapping_add(old[k].wrapping_sub(l[k]).wrapping_abs()));
        if diff < mindiff && n > 0 {
            mindiff = diff;
        }
        old = l;
    }
    minint.iter().for_each(|&m| int(o, m));
    maxint.iter().for_each(|&m| int(o, m));
    if (0..3).any(|k| maxint[k] as f32 - minint[k] as f32 >= MAXABS) {
        ok = false;
    }
    let sizeint: [u32; 3] = std::array::from_fn(|k| maxint[k].wrapping_sub(minint[k]).wrapping_add(1) as u32);
    let (bitsizeint, bitsize) = if (sizeint[0] | sizeint[1] | sizeint[2]) > 0xff_ffff {
        (sizeint.map(|s| bits_of_int(s as i32)), 0)
    } else {
        ([0; 3], bits_of_ints(sizeint))
    };
    let mut smallidx = FIRSTIDX;
    while smallidx < LASTIDX && MAGICINTS[smallidx] < mindiff {
        smallidx += 1;
    }
    int(o, smallidx as i32);
    let maxidx = LASTIDX.min(smallidx + 8);
    let minidx = maxidx - 8;
    let mut smaller = MAGICINTS[FIRSTIDX.max(smallidx - 1)] / 2;
    let mut small = MAGICINTS[smallidx] / 2;
    let mut sizesmall = [MAGICINTS[smallidx] as u32; 3];
    let larger = MAGICINTS[maxidx] / 2;
    let mut bits = Bits::default();
    let (mut prevcoord, mut prevrun) = ([0i32; 3], -1i32);
    let near = |a: &[i32], b: &[i32], lim: i32| (0..3).all(|k| a[k].wrapping_sub(b[k]).wrapping_abs() < lim);
    let mut i = 0;
    let mut tmpcoord = [0u32; 30];
    while i < size {
        let mut is_small = false;
        let mut is_smaller: i32 = if smallidx < maxidx && i >= 1 && near(&ip[3 * i..3 * i + 3], &prevcoord, larger) {
            1
        } else if smallidx > minidx {
            -1
        } else {
            0
        };
        if i + 1 < size && near(&ip[3 * i..3 * i + 3], &ip[3 * i + 3..3 * i + 6], small) {
            // the first two swapped (water: the hydrogen before the oxygen)
            for k in 0..3 {
                ip.swap(3 * i + k, 3 * i + 3 + k);
            }
            is_small = true;
        }
        let this: [i32; 3] = std::array::from_fn(|k| ip[3 * i + k]);
        let t: [u32; 3] = std::array::from_fn(|k| this[k].wrapping_sub(minint[k]) as u32);
        if bitsize == 0 {
            (0..3).for_each(|k| bits.send(bitsizeint[k], t[k]));
        } else {
            bits.send_ints(bitsize, sizeint, t);
        }
        prevcoord = this;
        i += 1;
        let mut run = 0;
        if !is_small && is_smaller == -1 {
            is_smaller = 0;
        }
        while is_small && run < 8 * 3 {
            let this = &ip[3 * i..3 * i + 3];
            let d2 = (0..3).fold(0i32, |s, k| {
                let d = this[k].wrapping_sub(prevcoord[k]);
                s.wrapping_add(d.wrapping_mul(d))
            });
            if is_smaller == -1 && d2 >= smaller * smaller {
                is_smaller = 0;
            }
            for k in 0..3 {
                tmpcoord[run] = this[k].wrapping_sub(prevcoord[k]).wrapping_add(small) as u32;
                run += 1;
            }
            prevcoord = [this[0], this[1], this[2]];
            i += 1;
            is_small = i < size && near(&ip[3 * i..3 * i + 3], &prevcoord, small);
        }
        if run as i32 != prevrun || is_smaller != 0 {
            prevrun = run as i32;
            bits.send(1, 1);
            bits.send(5, (run as i32 + is_smaller + 1) as u32);
        } else {
            bits.send(1, 0);
        }
        for k in (0..run).step_by(3) {
            bits.send_ints(smallidx as u32, sizesmall, [tmpcoord[k], tmpcoord[k + 1], tmpcoord[k + 2]]);
        }
        if is_smaller != 0 {
            smallidx = (smallidx as i32 + is_smaller) as usize;
            if is_smaller < 0 {
                small = smaller;
                smaller = MAGICINTS[smallidx - 1] / 2;
            } else {
                smaller = small;
                small = MAGICINTS[smallidx] / 2;
            }
            sizesmall = [MAGICINTS[smallidx] as u32; 3];
        }
    }
    let bytes = bits.finish();
    int(o, bytes.len() as i32);
    o.extend_from_slice(&bytes);
    o.resize(o.len().next_multiple_of(4), 0);
    ok
}
