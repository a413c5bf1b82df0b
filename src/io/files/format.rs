//! Number formatting for Triangle's file layouts, appended to a byte buffer without allocating:
//! C's `%.17g` for reals and `%d`/`%4d` for integers.

use std::fmt::Write as _;

/// Significant digits of `%.17g`: enough to read every `f64` back exactly.
const SIGNIFICANT_DIGITS: i32 = 17;

/// A fixed-size stack buffer that `write!` can format into (the longest `{:.16e}` of an `f64`
/// is 24 bytes: sign, 17 digits, the point, `e`, sign and 3 exponent digits).
struct StackText {
    bytes: [u8; 40],
    len: usize,
}

impl std::fmt::Write for StackText {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let end = self.len + s.len();
        if end > self.bytes.len() {
            return Err(std::fmt::Error);
        }
        self.bytes[self.len..end].copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// Appends `value` exactly as C's `printf("%.17g", value)` prints it (glibc): 17 significant
/// digits, correctly rounded (ties to even); exponent form (`1e-05`, `1.0000000000000001e+20`)
/// when the decimal exponent is below -4 or at least 17, fixed form otherwise; trailing zeros and
/// a trailing point removed; `inf`, `-inf`, `nan`, `-nan`, `-0` as glibc writes them.
pub fn push_g17(out: &mut Vec<u8>, value: f64) {
    if value.is_sign_negative() {
        out.push(b'-');
    }
    if value.is_nan() {
        out.extend_from_slice(b"nan");
        return;
    }
    if value.is_infinite() {
        out.extend_from_slice(b"inf");
        return;
    }
    if value == 0.0 {
        out.push(b'0');
        return;
    }
    // Integers below 2^53 have at most 16 digits: %.17g prints them exactly, without a point.
    if value.fract() == 0.0 && value.abs() < 9.0e15 {
        push_unsigned(out, value.abs() as u64);
        return;
    }
    let (mut digits, exponent) = match seventeen_digits(value.abs()) {
        Some(found) => found,
        None => seventeen_digits_by_fmt(value.abs()),
    };
    // Trailing zeros are never printed by %g (without the `#` flag).
    let mut significant = digits.len();
    while significant > 1 && digits[significant - 1] == b'0' {
        significant -= 1;
    }
    let digits = &mut digits[..significant];
    push_g_layout(out, digits, exponent);
}

/// The 17 significant digits of `x` (positive, finite), correctly rounded with ties to even on
/// the exact binary value, and the decimal exponent after rounding, in integer arithmetic: `x` =
/// m · 2^q is scaled by 10^(16 − E) exactly in 128 bits and shifted back with the remainder
/// deciding the rounding. `None` outside the range where that fits (decimal exponents from −6 to
/// 16 and q ≤ 0: every coordinate of ordinary magnitude); the caller then uses `fmt`.
fn seventeen_digits(x: f64) -> Option<([u8; 17], i32)> {
    const TEN16: u128 = 10_000_000_000_000_000;
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    if biased == 0 {
        return None; // subnormal: far outside the range
    }
    let m = u128::from((bits & ((1 << 52) - 1)) | (1 << 52));
    let q = biased - 1075;
    if q > 0 {
        return None;
    }
    let shift = (-q) as u32;
    // A first guess of E = floor(log10 x), corrected below against the exact value.
    let mut e = x.log10().floor() as i32;
    for _ in 0..3 {
        if !(-6..=16).contains(&e) || shift >= 128 {
            return None;
        }
        let scaled = m * 10u128.pow((16 - e) as u32); // < 2^53 · 10^22 < 2^127
        let whole = scaled >> shift;
        if whole < TEN16 {
            e -= 1;
            continue;
        }
        if whole >= 10 * TEN16 {
            e += 1;
            continue;
        }
        let remainder = scaled - (whole << shift);
        let half = if shift == 0 { 0 } else { 1u128 << (shift - 1) };
        let round_up = shift > 0 && (remainder > half || (remainder == half && whole % 2 == 1));
        let mut rounded = whole + u128::from(round_up);
        if rounded == 10 * TEN16 {
            rounded = TEN16;
            e += 1;
        }
        let (text, start) = unsigned_digits(rounded as u64);
        let mut digits = [0u8; 17];
        digits.copy_from_slice(&text[start..]);
        return Some((digits, e));
    }
    None
}

/// As [`seventeen_digits`], for every positive finite `x`, by Rust's fixed-precision scientific
/// formatting: correctly rounded (ties to even on the exact binary value), as glibc's printf is;
/// `%g` takes its exponent after this rounding.
fn seventeen_digits_by_fmt(x: f64) -> ([u8; 17], i32) {
    let mut text = StackText {
        bytes: [0; 40],
        len: 0,
    };
    write!(text, "{:.*e}", (SIGNIFICANT_DIGITS - 1) as usize, x)
        .expect("an f64 in scientific form fits in 40 bytes");
    let text = &text.bytes[..text.len];
    let e_at = text
        .iter()
        .position(|&b| b == b'e')
        .expect("scientific form has an exponent");
    let exponent: i32 = std::str::from_utf8(&text[e_at + 1..])
        .ok()
        .and_then(|s| s.parse().ok())
        .expect("the exponent is a decimal integer");
    // The 17 significant digits, without the point.
    let mut digits = [0u8; SIGNIFICANT_DIGITS as usize];
    let mut count = 0;
    for &b in &text[..e_at] {
        if b.is_ascii_digit() {
            digits[count] = b;
            count += 1;
        }
    }
    debug_assert_eq!(count, SIGNIFICANT_DIGITS as usize);
    (digits, exponent)
}

/// `%g`'s layout of the significant `digits` (trailing zeros removed) with decimal `exponent`:
/// exponent form below -4 or from 17 on, fixed form otherwise.
fn push_g_layout(out: &mut Vec<u8>, digits: &[u8], exponent: i32) {
    if !(-4..SIGNIFICANT_DIGITS).contains(&exponent) {
        out.push(digits[0]);
        if digits.len() > 1 {
            out.push(b'.');
            out.extend_from_slice(&digits[1..]);
        }
        out.push(b'e');
        out.push(if exponent < 0 { b'-' } else { b'+' });
        let magnitude = exponent.unsigned_abs();
        if magnitude < 10 {
            out.push(b'0');
        }
        push_unsigned(out, magnitude as u64);
    } else if exponent >= 0 {
        let integer_digits = exponent as usize + 1;
        if digits.len() <= integer_digits {
            out.extend_from_slice(digits);
            out.extend(std::iter::repeat_n(b'0', integer_digits - digits.len()));
        } else {
            out.extend_from_slice(&digits[..integer_digits]);
            out.push(b'.');
            out.extend_from_slice(&digits[integer_digits..]);
        }
    } else {
        out.extend_from_slice(b"0.");
        out.extend(std::iter::repeat_n(b'0', (-exponent - 1) as usize));
        out.extend_from_slice(digits);
    }
}

/// `value` as `%.17g` in a new `String` (tests, messages).
pub fn g17(value: f64) -> String {
    let mut out = Vec::with_capacity(24);
    push_g17(&mut out, value);
    String::from_utf8(out).expect("ASCII")
}

/// The decimal digits of `value`, right-aligned in a stack buffer: (buffer, index of the first
/// digit). Two digits per division, and 32-bit divisions while the value fits (most indices).
fn unsigned_digits(mut value: u64) -> ([u8; 20], usize) {
    const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
                                2021222324252627282930313233343536373839\
                                4041424344454647484950515253545556575859\
                                6061626364656667686970717273747576777879\
                                8081828384858687888990919293949596979899";
    let mut digits = [0u8; 20];
    let mut start = digits.len();
    while value > u32::MAX as u64 {
        let pair = (value % 100) as usize;
        value /= 100;
        start -= 2;
        digits[start..start + 2].copy_from_slice(&PAIRS[2 * pair..2 * pair + 2]);
    }
    let mut small = value as u32;
    while small >= 100 {
        let pair = (small % 100) as usize;
        small /= 100;
        start -= 2;
        digits[start..start + 2].copy_from_slice(&PAIRS[2 * pair..2 * pair + 2]);
    }
    if small >= 10 {
        start -= 2;
        digits[start..start + 2]
            .copy_from_slice(&PAIRS[2 * small as usize..2 * small as usize + 2]);
    } else {
        start -= 1;
        digits[start] = b'0' + small as u8;
    }
    (digits, start)
}

fn push_unsigned(out: &mut Vec<u8>, value: u64) {
    let (digits, start) = unsigned_digits(value);
    out.extend_from_slice(&digits[start..]);
}

/// Appends `value` as C's `%d`.
pub fn push_int(out: &mut Vec<u8>, value: i64) {
    push_int_width(out, value, 0);
}

/// Appends `value` as C's `%<width>d`: right-aligned, padded with spaces, never truncated.
pub fn push_int_width(out: &mut Vec<u8>, value: i64, width: usize) {
    let (digits, start) = unsigned_digits(value.unsigned_abs());
    let length = digits.len() - start + usize::from(value < 0);
    const SPACES: [u8; 16] = [b' '; 16];
    let mut pad = width.saturating_sub(length);
    while pad > 0 {
        let chunk = pad.min(SPACES.len());
        out.extend_from_slice(&SPACES[..chunk]);
        pad -= chunk;
    }
    if value < 0 {
        out.push(b'-');
    }
    out.extend_from_slice(&digits[start..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// glibc's own `%.17g`, the oracle.
    fn c_g17(value: f64) -> String {
        let mut buffer = [0u8; 64];
        // SAFETY: the buffer is 64 bytes, its size is passed, and the format takes one double.
        let n = unsafe {
            libc::snprintf(
                buffer.as_mut_ptr().cast(),
                buffer.len(),
                c"%.17g".as_ptr(),
                value,
            )
        };
        String::from_utf8(buffer[..n as usize].to_vec()).unwrap()
    }

    #[test]
    fn documented_examples() {
        assert_eq!(g17(0.4), "0.40000000000000002");
        assert_eq!(g17(1e-5), "1.0000000000000001e-05");
        // Doubles near 1e20 are 16384 apart: the next one after 1e20 prints with a final 2.
        assert_eq!(g17(1e20 + 16384.0), "1.0000000000000002e+20");
        assert_eq!(g17(1.2345e20), "1.2345e+20");
        assert_eq!(g17(1e20), "1e+20");
        assert_eq!(g17(0.0), "0");
        assert_eq!(g17(-0.0), "-0");
        assert_eq!(g17(1.0), "1");
        assert_eq!(g17(-2.5), "-2.5");
        assert_eq!(g17(0.0001), "0.0001");
        assert_eq!(g17(0.00001), "1.0000000000000001e-05");
        assert_eq!(g17(1e16), "10000000000000000");
        assert_eq!(g17(1e17), "1e+17");
        assert_eq!(g17(123456789.0), "123456789");
        assert_eq!(g17(f64::INFINITY), "inf");
        assert_eq!(g17(f64::NEG_INFINITY), "-inf");
        assert_eq!(g17(f64::NAN), "nan");
        assert_eq!(g17(-0.0625 - 5.6e-17), "-0.062500000000000056");
    }

    #[test]
    #[allow(clippy::excessive_precision)] // The literals are the exact values being tested.
    fn agrees_with_glibc_on_edge_cases() {
        let cases = [
            5e-324,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::EPSILON,
            1.0 / 3.0,
            2.0 / 3.0,
            0.1,
            0.2,
            0.3,
            9.9999999999999995e-5,
            0.000099999999999999991,
            99999999999999999.0,
            9.9999999999999998e16,
            1125899906842624.25, // ties at the 17th digit: rounds to even
            1125899906842624.75,
            1125899906842625.25,
            1125899906842625.75,
            4503599627370495.5,
            0.5,
            100.0,
            1e-4,
            1e-300,
            1e300,
            123456789012345678.0,
        ];
        for &value in &cases {
            for v in [value, -value] {
                assert_eq!(g17(v), c_g17(v), "value bits {:#x}", v.to_bits());
            }
        }
    }

    #[test]
    fn agrees_with_glibc_on_pseudo_random_values() {
        // A fixed 64-bit LCG: deterministic, spread over all exponents and mantissas.
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..20_000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let bits = state;
            let value = f64::from_bits(bits);
            if value.is_nan() {
                continue;
            }
            assert_eq!(g17(value), c_g17(value), "value bits {bits:#x}");
            // Also values of everyday magnitude with short decimal forms.
            let everyday = ((state >> 11) % 2_000_000) as f64 / 1024.0 - 900.0;
            assert_eq!(g17(everyday), c_g17(everyday));
        }
    }

    /// The integer fast path against glibc where it applies (decimal exponents −6 to 16): random
    /// mantissas at every binary exponent of that range, short decimals, and exact ties at the
    /// 17th digit (n + 1/4 and n + 3/4 with 16-digit n, where the 18th digit is a 5).
    #[test]
    fn the_integer_path_agrees_with_glibc() {
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            state
        };
        let mut fast = 0;
        for _ in 0..100_000 {
            let exponent = (next() % 80) as i64 - 22; // 2^-22 (≈ 2e-7) to 2^57 (≈ 1.4e17)
            let bits = ((exponent + 1023) as u64) << 52 | (next() >> 12);
            let value = f64::from_bits(bits);
            fast += usize::from(seventeen_digits(value).is_some());
            assert_eq!(g17(value), c_g17(value), "value bits {bits:#x}");
            let decimal =
                (next() % 10_000_000) as f64 / [1.0, 10.0, 1e3, 1e6, 1e9][(next() % 5) as usize];
            assert_eq!(g17(decimal), c_g17(decimal), "{decimal:e}");
            let n = (1u64 << 50) + next() % (1 << 50);
            for tie in [n as f64 + 0.25, n as f64 + 0.75, n as f64 + 0.5] {
                assert_eq!(g17(tie), c_g17(tie), "{tie:e}");
            }
        }
        assert!(fast > 80_000, "the integer path took only {fast} values");
    }

    #[test]
    fn integers_with_width() {
        let mut out = Vec::new();
        push_int_width(&mut out, 7, 4);
        push_int_width(&mut out, -1, 4);
        push_int_width(&mut out, 123456, 4);
        push_int(&mut out, i64::MIN);
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "   7  -1123456-9223372036854775808"
        );
        for value in [
            0i64,
            5,
            9,
            10,
            99,
            100,
            101,
            4294967295,
            4294967296,
            12345678901234,
            i64::MAX,
            -10,
            -99999,
        ] {
            let mut out = Vec::new();
            push_int_width(&mut out, value, 22);
            assert_eq!(String::from_utf8(out).unwrap(), format!("{value:22}"));
        }
    }
}
