//! How numbers are written in the tables: times with as many decimals as
//! they need, byte counts in B, KiB or MiB.

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
    }
}
