//! Parsers for the numbers on a command line, shared by the subcommands so that every flag is
//! checked as its twin in a scene file is: finite, and in the range its meaning allows (NaN is
//! never accepted).

/// `text` as a number of type `T`, or a message quoting it.
fn number<T: std::str::FromStr>(text: &str) -> Result<T, String> {
    text.parse()
        .map_err(|_| format!("'{text}' is not a number"))
}

/// A finite number ≥ 0 (`--exposure`).
pub fn non_negative_f32(text: &str) -> Result<f32, String> {
    let v: f32 = number(text)?;
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("must be a finite number ≥ 0, found {text}"))
    }
}

/// A finite number ≥ 0 (thresholds such as `--max-mse`).
pub fn non_negative_f64(text: &str) -> Result<f64, String> {
    let v: f64 = number(text)?;
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("must be a finite number ≥ 0, found {text}"))
    }
}

/// A finite number > 0 (`--target-mse`).
pub fn positive_f64(text: &str) -> Result<f64, String> {
    let v: f64 = number(text)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("must be a finite number > 0, found {text}"))
    }
}

/// A finite number > 0 (`--noise-threshold`).
pub fn positive_f32(text: &str) -> Result<f32, String> {
    let v: f32 = number(text)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("must be a finite number > 0, found {text}"))
    }
}

/// A number in [0, 1] (`--adc-bailout`).
pub fn unit_interval_f32(text: &str) -> Result<f32, String> {
    let v: f32 = number(text)?;
    if (0.0..=1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("must be between 0 and 1, found {text}"))
    }
}

/// `A..B` with A < B (`--sample-range`): samples A ≤ i < B.
pub fn sample_range(text: &str) -> Result<std::ops::Range<u32>, String> {
    let bad = || format!("'{text}' is not a sample range A..B of whole numbers");
    let (a, b) = text.split_once("..").ok_or_else(bad)?;
    let (a, b): (u32, u32) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if a < b {
        Ok(a..b)
    } else {
        Err(format!(
            "'{text}' is an empty sample range: A < B is needed"
        ))
    }
}

/// `A,B`: two whole numbers (`--tile`, `--tiles`).
pub fn pair(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}' is not a pair A,B of whole numbers");
    let (a, b) = text.split_once(',').ok_or_else(bad)?;
    Ok((
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    ))
}

/// The parser of every `--threads` flag: a whole number of worker threads, 1 to 4096.
pub fn thread_count() -> clap::builder::RangedU64ValueParser<u64> {
    clap::value_parser!(u64).range(1..=4096)
}

/// A rayon pool of `threads` workers (all cores for `None`).
pub fn thread_pool(threads: Option<u64>) -> Result<rayon::ThreadPool, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0) as usize)
        .build()
        .map_err(|e| format!("cannot start worker threads: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_infinity_and_out_of_range_values_are_refused() {
        for bad in ["nan", "NaN", "inf", "-inf", "-1", "x", ""] {
            assert!(non_negative_f32(bad).is_err(), "{bad}");
            assert!(non_negative_f64(bad).is_err(), "{bad}");
            assert!(positive_f64(bad).is_err(), "{bad}");
            assert!(unit_interval_f32(bad).is_err(), "{bad}");
        }
        assert!(positive_f64("0").is_err());
        assert!(unit_interval_f32("1.5").is_err());
        assert_eq!(non_negative_f32("0"), Ok(0.0));
        assert_eq!(unit_interval_f32("1"), Ok(1.0));
        assert_eq!(positive_f64("1e-9"), Ok(1e-9));
    }
}
