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
    match seventeen_digits(value.abs()) {
        Some((digits, exponent)) => push_g_layout_of_integer(out, digits, exponent),
        None => {
            let (digits, exponent) = seventeen_digits_by_fmt(value.abs());
            // Trailing zeros are never printed by %g (without the `#` flag).
            let mut significant = digits.len();
            while significant > 1 && digits[significant - 1] == b'0' {
                significant -= 1;
            }
            push_g_layout(out, &digits[..significant], exponent);
        }
    }
}

/// 10^k for k = 0 to 22: every power of ten that [`seventeen_digits`] scales by and [`decimal_length`] compares with.
const POWERS_OF_TEN: [u128; 23] = {
    let mut table = [1u128; 23];
    let mut k = 1;
    while k < 23 {
        table[k] = table[k - 1] * 10;
        k += 1;
    }
    table
};

/// The 17 significant digits of `x` (positive, finite) as an integer from 10^16 to 10^17 − 1,
/// correctly rounded with ties to even on the exact binary value, and the decimal exponent
/// after rounding, in integer arithmetic: `x` = m · 2^q is scaled by 10^(16 − E) exactly in 128
/// bits and shifted back with the remainder deciding the rounding. `None` outside the range
/// where that fits (decimal exponents from −6 to 16 and q ≤ 0: every coordinate of ordinary
/// magnitude); the caller then uses `fmt`.
fn seventeen_digits(x: f64) -> Option<(u64, i32)> {
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
    // A first guess of E = floor(log10 x) from the binary exponent: x lies in [2^k, 2^(k+1))
    // with k = q + 52, and floor(k · log10 2) = (k · 78913) >> 18 for |k| < 1000; E is that or
    // one more. The loop below checks it against the exact value (from −6: below that the
    // table has no power, and the check steps down to −7 and gives up).
    let mut e = (((q + 52) * 78913) >> 18).max(-6);
    for _ in 0..3 {
        if !(-6..=16).contains(&e) || shift >= 128 {
            return None;
        }
        let scaled = m * POWERS_OF_TEN[(16 - e) as usize]; // < 2^53 · 10^22 < 2^127
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
        return Some((rounded as u64, e));
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
        push_exponent(out, exponent);
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

/// `%g`'s exponent: `e`, its sign, and at least two digits.
fn push_exponent(out: &mut Vec<u8>, exponent: i32) {
    out.push(b'e');
    out.push(if exponent < 0 { b'-' } else { b'+' });
    let magnitude = exponent.unsigned_abs();
    if magnitude < 10 {
        out.push(b'0');
    }
    push_unsigned(out, magnitude as u64);
}

/// [`push_g_layout`] for the 17 digits of `digits` (10^16 ≤ `digits` < 10^17) with decimal
/// `exponent` from −6 to 16 (what [`seventeen_digits`] gives), written in place: the digits go
/// straight to their final bytes (no copy through a stack buffer, whose narrow stores read back
/// wide would stall the store forwarding), the point is put in by moving the integer digits
/// one place left, and trailing zeros are cut off.
fn push_g_layout_of_integer(out: &mut Vec<u8>, digits: u64, exponent: i32) {
    // Room for the longest layout, "0.000" and 17 digits; truncated below.
    let at = out.len();
    out.extend_from_slice(&[b'0'; 24]);
    let text = &mut out[at..];
    let (first_digit, end) = match exponent {
        // 17 integer digits: nothing after them, no point.
        16 => {
            write_17_digits(text, 0, digits);
            out.truncate(at + 17);
            return;
        }
        0..=15 => {
            let point = exponent as usize + 1;
            write_17_digits(text, 1, digits);
            text.copy_within(1..=point, 0);
            text[point] = b'.';
            (point + 1, 18)
        }
        -4..=-1 => {
            // "0." and −exponent − 1 zeros (already in place) before the digits.
            let start = 1 + exponent.unsigned_abs() as usize;
            text[1] = b'.';
            write_17_digits(text, start, digits);
            (start + 1, start + 17)
        }
        _ => {
            // d.dddddddddddddddde-0x (only −6 and −5 reach here).
            write_17_digits(text, 1, digits);
            text[0] = text[1];
            text[1] = b'.';
            (2, 18)
        }
    };
    let mut end = end;
    while end > first_digit && text[end - 1] == b'0' {
        end -= 1;
    }
    if text[end - 1] == b'.' {
        end -= 1;
    }
    out.truncate(at + end);
    if exponent < -4 {
        push_exponent(out, exponent);
    }
}

/// Two decimal digits per entry, for 0 to 99 (values of 10^8 and more).
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
                            2021222324252627282930313233343536373839\
                            4041424344454647484950515253545556575859\
                            6061626364656667686970717273747576777879\
                            8081828384858687888990919293949596979899";

/// The 8 decimal digits of `value` (below 10^8, leading zeros included) as ASCII bytes in a
/// little-endian word (the first digit in the lowest byte), computed in parallel within the
/// word (SWAR): the two 4-digit halves in 32-bit lanes, split into pairs in 16-bit lanes, then
/// into digits in bytes. Each split divides by 100 or 10 with a multiply and shift that is exact
/// for the lane's range (n·10486 >> 20 = ⌊n/100⌋ for n < 10^4; m·103 >> 10 = ⌊m/10⌋ for
/// m < 100) and whose products stay inside their lanes.
#[inline(always)]
fn eight_digits(value: u32) -> u64 {
    let value = u64::from(value);
    let halves = (value / 10_000) | ((value % 10_000) << 32);
    let hundreds = ((halves * 10_486) >> 20) & 0x0000_007f_0000_007f;
    let pairs = hundreds | ((halves - hundreds * 100) << 16);
    let tens = ((pairs * 103) >> 10) & 0x000f_000f_000f_000f;
    let digits = tens | ((pairs - tens * 10) << 8);
    digits | 0x3030_3030_3030_3030
}

/// Writes `value` (below 10^17) as exactly 17 digits at `text[at..at + 17]`.
#[inline(always)]
fn write_17_digits(text: &mut [u8], at: usize, value: u64) {
    let (high, low) = (value / 100_000_000, (value % 100_000_000) as u32);
    text[at] = b'0' + (high / 100_000_000) as u8;
    text[at + 1..at + 9].copy_from_slice(&eight_digits((high % 100_000_000) as u32).to_le_bytes());
    text[at + 9..at + 17].copy_from_slice(&eight_digits(low).to_le_bytes());
}

/// `value` as `%.17g` in a new `String` (tests, messages).
pub fn g17(value: f64) -> String {
    let mut out = Vec::with_capacity(24);
    push_g17(&mut out, value);
    String::from_utf8(out).expect("ASCII")
}

/// The number of decimal digits of `value` (1 for 0): from its bit length, which gives the
/// digit count or one more, and one comparison.
fn decimal_length(value: u64) -> usize {
    let bits = 64 - (value | 1).leading_zeros();
    // ⌊bits · log10 2⌋ (1233 / 4096 ≈ log10 2): the number of digits of 2^(bits−1), minus one.
    let guess = ((bits * 1233) >> 12) as usize;
    guess + usize::from(u128::from(value | 1) >= POWERS_OF_TEN[guess])
}

/// Appends the decimal digits of `value`: below 10^8 (vertex and triangle numbers) as
/// [`eight_digits`] with the leading zeros shifted out, one 8-byte store; larger values from
/// the last digit back, two at a time.
fn push_unsigned(out: &mut Vec<u8>, value: u64) {
    if value < 100_000_000 {
        let digits = eight_digits(value as u32);
        // Leading zero digits are the low bytes that hold b'0' (a lone 0 keeps one).
        let zeros = (((digits ^ 0x3030_3030_3030_3030).trailing_zeros() / 8) as usize).min(7);
        let at = out.len();
        out.extend_from_slice(&(digits >> (8 * zeros)).to_le_bytes());
        out.truncate(at + 8 - zeros);
        return;
    }
    let length = decimal_length(value);
    let at = out.len();
    out.extend_from_slice(&[b'0'; 20]);
    let text = &mut out[at..at + length];
    let mut end = length;
    let mut value = value;
    while value > u64::from(u32::MAX) {
        let pair = (value % 100) as usize;
        value /= 100;
        end -= 2;
        text[end..end + 2].copy_from_slice(&PAIRS[2 * pair..2 * pair + 2]);
    }
    let mut small = value as u32;
    while small >= 100 {
        let pair = (small % 100) as usize;
        small /= 100;
        end -= 2;
        text[end..end + 2].copy_from_slice(&PAIRS[2 * pair..2 * pair + 2]);
    }
    if small >= 10 {
        text[end - 2..end].copy_from_slice(&PAIRS[2 * small as usize..2 * small as usize + 2]);
    } else {
        text[end - 1] = b'0' + small as u8;
    }
    out.truncate(at + length);
}

/// Appends `value` as C's `%d`.
pub fn push_int(out: &mut Vec<u8>, value: i64) {
    push_int_width(out, value, 0);
}

/// Appends `value` as C's `%<width>d`: right-aligned, padded with spaces, never truncated.
pub fn push_int_width(out: &mut Vec<u8>, value: i64, width: usize) {
    let magnitude = value.unsigned_abs();
    let length = decimal_length(magnitude) + usize::from(value < 0);
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
    push_unsigned(out, magnitude);
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

    /// Decimal exponents change at powers of ten: the first guess of the exponent (from the
    /// binary one) is one short just above them. Powers of ten and their neighbouring doubles.
    #[test]
    fn agrees_with_glibc_around_powers_of_ten() {
        for k in -9..=19 {
            let power = 10f64.powi(k);
            let mut value = power;
            for _ in 0..3 {
                value = f64::from_bits(value.to_bits() - 1);
            }
            for _ in 0..7 {
                assert_eq!(
                    g17(value),
                    c_g17(value),
                    "value bits {:#x}",
                    value.to_bits()
                );
                value = f64::from_bits(value.to_bits() + 1);
            }
        }
    }

    #[test]
    fn eight_digits_and_unsigned_integers() {
        let check = |value: u64| {
            let mut out = b"x".to_vec();
            push_unsigned(&mut out, value);
            assert_eq!(out, format!("x{value}").into_bytes(), "{value}");
            if value < 100_000_000 {
                let digits = eight_digits(value as u32).to_le_bytes();
                assert_eq!(digits, *format!("{value:08}").as_bytes(), "{value}");
            }
        };
        (0..200_000).for_each(check);
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            check(state >> (state % 64));
            check((state >> 32) % 100_000_000);
        }
        for value in [
            99_999_999,
            100_000_000,
            100_000_001,
            10_000_000,
            9_999_999,
            u64::MAX,
        ] {
            check(value);
        }
    }

    #[test]
    fn decimal_lengths() {
        let mut power = 1u64;
        for digits in 1..=19 {
            assert_eq!(decimal_length(power), digits);
            assert_eq!(decimal_length(power - 1), (digits - 1).max(1));
            assert_eq!(decimal_length(power + 1), digits);
            power *= 10;
        }
        assert_eq!(decimal_length(u64::MAX), 20);
        assert_eq!(decimal_length(0), 1);
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
