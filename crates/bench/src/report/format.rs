//! How numbers are written in the tables: times with as many decimals as
//! they need, byte counts in B, KiB or MiB, counts with separators, errors
//! and shares in two significant digits (an exact 0 as `0`).

/// Milliseconds: no decimals from 100 ms, two from 1 ms, three below.
pub(super) fn fmt_ms(ms: f64) -> String {
    if ms >= 100.0 {
        format!("{ms:.0}")
    } else if ms >= 1.0 {
        format!("{ms:.2}")
    } else {
        format!("{ms:.3}")
    }
}

/// Bytes, in MiB from 10 MiB, in KiB from 10 KiB, else in bytes.
pub(super) fn fmt_bytes(b: u64) -> String {
    if b >= 10 << 20 {
        format!("{} MiB", b >> 20)
    } else if b >= 10 << 10 {
        format!("{} KiB", b >> 10)
    } else {
        format!("{b} B")
    }
}

/// A scaling axis value: no decimals from 100, two below.
pub(super) fn fmt_axis(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else {
        format!("{x:.2}")
    }
}

/// A count with thousands separated by commas: `12,345`.
pub(super) fn fmt_count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// An error value in two significant digits, `0` for exactly 0 and for
/// rounding noise (below 1e-12), never `0.00e0`.
pub(super) fn fmt_error(e: f64) -> String {
    if e.abs() < 1e-12 {
        "0".into()
    } else if (1e-3..100.0).contains(&e.abs()) {
        let digits = (1 - e.abs().log10().floor() as i32).max(0) as usize;
        format!("{e:.digits$}")
    } else {
        format!("{e:.1e}")
    }
}

/// A share as a percentage: `0`, `0.012%`, `3.4%`, `100%`.
pub(super) fn fmt_pct(share: f64) -> String {
    let p = share * 100.0;
    if p == 0.0 {
        "0".into()
    } else if p.abs() >= 10.0 {
        format!("{p:.0}%")
    } else if p.abs() >= 0.1 {
        format!("{p:.1}%")
    } else {
        format!("{}%", fmt_error(p))
    }
}

/// A ratio of times: `2.3x`, `15x`.
pub(super) fn fmt_ratio(r: f64) -> String {
    if r >= 10.0 {
        format!("{r:.0}x")
    } else {
        format!("{r:.2}x")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_the_digits_that_matter() {
        assert_eq!(fmt_ms(123.456), "123");
        assert_eq!(fmt_ms(1.234_56), "1.23");
        assert_eq!(fmt_ms(0.123_456), "0.123");
        assert_eq!(fmt_bytes(10 << 20), "10 MiB");
        assert_eq!(fmt_bytes(10 << 10), "10 KiB");
        assert_eq!(fmt_bytes(10_239), "10239 B");
        assert_eq!(fmt_axis(1024.0), "1024");
        assert_eq!(fmt_axis(2.5), "2.50");
        assert_eq!(fmt_count(1_234_567), "1,234,567");
        assert_eq!(fmt_count(999), "999");
        assert_eq!(fmt_error(0.0), "0");
        assert_eq!(fmt_error(4.5e-16), "0");
        assert_eq!(fmt_error(0.0123), "0.012");
        assert_eq!(fmt_error(7.8e-5), "7.8e-5");
        assert_eq!(fmt_pct(0.0), "0");
        assert_eq!(fmt_pct(0.5), "50%");
        assert_eq!(fmt_pct(0.034), "3.4%");
        assert_eq!(fmt_pct(0.00012), "0.012%");
        assert_eq!(fmt_ratio(2.345), "2.35x");
        assert_eq!(fmt_ratio(14.6), "15x");
    }
}
