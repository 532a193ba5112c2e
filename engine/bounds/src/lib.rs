//! Figures held to limits: the one way Headlamp's tests, `bench`'s tests and `replay --goldens`
//! decide whether a number passes.
//!
//! `error > limit` is false when `error` is NaN, and `f64::max` drops a NaN, so a GI that wrote
//! NaN into every pixel would pass a check written with either. Here a figure that is NaN or
//! infinite fails whatever its limit, and every failure names the figure.
//!
//! A limit that states how good something is, a tolerance, is declared with [`tolerance!`]
//! beside what it measured when it was set, so that docs/testing.md can list each limit beside
//! its measured worst (a test keeps that table equal to the declarations).

use std::fmt::Display;

/// How a figure is held to its limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// The figure is at most the limit.
    AtMost,
    /// The figure is at least the limit.
    AtLeast,
    /// The figure's magnitude is at most the limit (a signed error, such as an energy gain).
    Magnitude,
}

impl Kind {
    /// The relation as written in messages and in docs/testing.md's table.
    pub fn symbol(self) -> &'static str {
        match self {
            Kind::AtMost => "≤",
            Kind::AtLeast => "≥",
            Kind::Magnitude => "|x| ≤",
        }
    }

    /// Whether a finite `value` keeps to `limit`.
    fn holds(self, value: f64, limit: f64) -> bool {
        match self {
            Kind::AtMost => value <= limit,
            Kind::AtLeast => value >= limit,
            Kind::Magnitude => value.abs() <= limit,
        }
    }
}

/// Holds `value`, the figure called `figure`, to `limit`: `Err` names the figure, its value and
/// the limit when the value is NaN, infinite, or on the wrong side.
pub fn check(figure: impl Display, value: impl Into<f64>, kind: Kind, limit: impl Into<f64>) -> Result<(), String> {
    let (value, limit, op) = (value.into(), limit.into(), kind.symbol());
    if !value.is_finite() {
        return Err(format!("{figure} is {value}, not a finite number (its limit: {op} {limit})"));
    }
    if !kind.holds(value, limit) {
        return Err(format!("{figure} is {}, past its limit: {op} {limit}", shown(value)));
    }
    Ok(())
}

/// `value` with six decimals, or in scientific notation where those would hide it.
fn shown(value: f64) -> String {
    if value != 0.0 && value.abs() < 1e-3 {
        format!("{value:.3e}")
    } else {
        format!("{value:.6}")
    }
}

/// [`check`] that `value` is at most `limit`.
pub fn at_most(figure: impl Display, value: impl Into<f64>, limit: impl Into<f64>) -> Result<(), String> {
    check(figure, value, Kind::AtMost, limit)
}

/// [`check`] that `value` is at least `floor`.
pub fn at_least(figure: impl Display, value: impl Into<f64>, floor: impl Into<f64>) -> Result<(), String> {
    check(figure, value, Kind::AtLeast, floor)
}

/// [`check`] that `value` is within `limit` of zero either way.
pub fn magnitude_at_most(figure: impl Display, value: impl Into<f64>, limit: impl Into<f64>) -> Result<(), String> {
    check(figure, value, Kind::Magnitude, limit)
}

/// Panics with the message of a failed check; returns nothing otherwise. For one check in a
/// test: `bounds::assert(bounds::at_least("lit pixels", n as f64, 50.0))`.
#[track_caller]
pub fn assert(result: Result<(), String>) {
    if let Err(e) = result {
        panic!("{e}");
    }
}

/// Panics listing every failed check, one a line; returns nothing when all passed.
#[track_caller]
pub fn assert_all(results: impl IntoIterator<Item = Result<(), String>>) {
    let failures: Vec<String> = results.into_iter().filter_map(Result::err).collect();
    if !failures.is_empty() {
        panic!("{} failed:\n{}", failures.len(), failures.join("\n"));
    }
}

/// The largest of `values`, and NaN if any is NaN or there are none (`f64::max` would drop a
/// NaN; nothing measured must not read as a pass).
pub fn worst(values: impl IntoIterator<Item = f64>) -> f64 {
    let mut worst: Option<f64> = None;
    for v in values {
        if v.is_nan() {
            return f64::NAN;
        }
        worst = Some(match worst {
            Some(w) if w >= v => w,
            _ => v,
        });
    }
    worst.unwrap_or(f64::NAN)
}

/// The smallest of `values`, and NaN if any is NaN or there are none.
pub fn least(values: impl IntoIterator<Item = f64>) -> f64 {
    -worst(values.into_iter().map(|v| -v))
}

/// A limit on how good something is, and what it measured when the limit was set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Where it is declared and its name: `plugin_gi/tests/accuracy.rs: GOAL`.
    pub name: &'static str,
    pub kind: Kind,
    pub limit: f64,
    /// The worst figure it held when it was set, over every case it is applied to (the
    /// largest for [`Kind::AtMost`], the largest magnitude for [`Kind::Magnitude`], the
    /// smallest for [`Kind::AtLeast`]).
    pub measured: f64,
    /// Why the limit leaves more than twice the measured worst's room, where it does.
    pub wider: Option<&'static str>,
}

impl Tolerance {
    /// Holds `value`, the figure called `figure`, to this tolerance (see [`check`]), and
    /// prints the figure with the tolerance's name either way: the test output shows what each
    /// tolerance measures today.
    pub fn check(&self, figure: impl Display, value: impl Into<f64>) -> Result<(), String> {
        let value = value.into();
        let result = check(&figure, value, self.kind, self.limit).map_err(|e| format!("{e} [{}]", self.name));
        let verdict = if result.is_ok() { "ok" } else { "FAILED" };
        println!(
            "tolerance {verdict} [{}] {figure}: {} ({} {})",
            self.name,
            shown(value),
            self.kind.symbol(),
            self.limit
        );
        result
    }

    /// [`Tolerance::check`], panicking with its message on a failure.
    #[track_caller]
    pub fn assert(&self, figure: impl Display, value: impl Into<f64>) {
        assert(self.check(figure, value));
    }

    /// How much room the limit leaves over the measured worst: limit ÷ measured (measured ÷
    /// limit for a floor): 1 for an exact check, a limit of 0 that measured 0.
    pub fn room(&self) -> f64 {
        if self.limit == self.measured {
            return 1.0;
        }
        match self.kind {
            Kind::AtMost | Kind::Magnitude => self.limit / self.measured.abs(),
            Kind::AtLeast => self.measured / self.limit,
        }
    }
}

/// Declares a [`Tolerance`] constant named after itself and the file it is in:
///
/// ```
/// bounds::tolerance! {
///     /// The GI's block error against the exact bounce.
///     pub BLOCK_ERROR: at_most 0.05, measured 0.0463
/// }
/// bounds::tolerance!(LEAK: at_most 0.0012, measured 0.0006);
/// bounds::tolerance!(ENERGY: magnitude 0.03, measured 0.021);
/// bounds::tolerance!(CHANGE: at_least 0.01, measured 0.019);
/// bounds::tolerance!(SEAM: at_most 0.2, measured 0.07, wider "frames where a receiver lies on the seam");
/// assert!(BLOCK_ERROR.check("box", 0.04).is_ok() && BLOCK_ERROR.check("box", f64::NAN).is_err());
/// ```
#[macro_export]
macro_rules! tolerance {
    ($(#[$a:meta])* $v:vis $name:ident: at_most $limit:literal, measured $m:literal $(, wider $why:literal)? $(;)?) => {
        $crate::__tolerance!($(#[$a])* $v $name, AtMost, $limit, $m $(, $why)?);
    };
    ($(#[$a:meta])* $v:vis $name:ident: at_least $limit:literal, measured $m:literal $(, wider $why:literal)? $(;)?) => {
        $crate::__tolerance!($(#[$a])* $v $name, AtLeast, $limit, $m $(, $why)?);
    };
    ($(#[$a:meta])* $v:vis $name:ident: magnitude $limit:literal, measured $m:literal $(, wider $why:literal)? $(;)?) => {
        $crate::__tolerance!($(#[$a])* $v $name, Magnitude, $limit, $m $(, $why)?);
    };
}

#[doc(hidden)]
#[macro_export]
macro_rules! __tolerance {
    ($(#[$a:meta])* $v:vis $name:ident, $kind:ident, $limit:literal, $m:literal) => {
        $crate::__tolerance!(@ $(#[$a])* $v $name, $kind, $limit, $m, None);
    };
    ($(#[$a:meta])* $v:vis $name:ident, $kind:ident, $limit:literal, $m:literal, $why:literal) => {
        $crate::__tolerance!(@ $(#[$a])* $v $name, $kind, $limit, $m, Some($why));
    };
    (@ $(#[$a:meta])* $v:vis $name:ident, $kind:ident, $limit:literal, $m:literal, $why:expr) => {
        $(#[$a])*
        $v const $name: $crate::Tolerance = $crate::Tolerance {
            name: concat!(file!(), ": ", stringify!($name)),
            kind: $crate::Kind::$kind,
            limit: $limit,
            measured: $m,
            wider: $why,
        };
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    tolerance! {
        /// A tolerance of this file's tests.
        ERROR: at_most 0.05, measured 0.03
    }
    tolerance!(GAIN: magnitude 0.03, measured 0.02);
    tolerance!(FLOOR: at_least 0.5, measured 0.8, wider "a floor");

    #[test]
    fn nan_and_infinity_fail_every_check_naming_the_figure() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for kind in [Kind::AtMost, Kind::AtLeast, Kind::Magnitude] {
                let e = check("the red room's block error", bad, kind, 1.0).unwrap_err();
                assert!(e.contains("the red room's block error") && e.contains("not a finite number"), "{e}");
            }
            for e in [
                at_most("flicker", bad, 0.01),
                at_least("lit pixels", bad, 50.0),
                magnitude_at_most("energy", bad, 0.03),
                ERROR.check("face-on error", bad),
                GAIN.check("face-on energy", bad),
                FLOOR.check("leak without visibility", bad),
            ]
            .map(Result::unwrap_err)
            {
                assert!(e.contains("not a finite number"), "{e}");
            }
        }
    }

    #[test]
    fn each_kind_holds_its_side_and_names_the_limit_when_it_fails() {
        assert!(at_most("x", 0.05, 0.05).is_ok() && at_most("x", 0.0501, 0.05).is_err());
        assert!(at_least("x", 2.0, 2.0).is_ok() && at_least("x", 1.99, 2.0).is_err());
        assert!(magnitude_at_most("x", -0.03, 0.03).is_ok() && magnitude_at_most("x", -0.031, 0.03).is_err());
        let e = ERROR.check("hall, cuts: block error", 0.06).unwrap_err();
        assert!(e.contains("hall, cuts: block error is 0.060000, past its limit: ≤ 0.05"), "{e}");
        assert!(e.contains("engine/bounds/src/lib.rs: ERROR"), "the tolerance is named: {e}");
    }

    #[test]
    fn worst_and_least_keep_a_nan_and_nothing_is_nan() {
        assert_eq!(worst([0.1, 0.3, 0.2]), 0.3);
        assert_eq!(least([0.1, 0.3, 0.2]), 0.1);
        assert!(worst([0.1, f64::NAN, 0.2]).is_nan() && worst([f64::NAN]).is_nan());
        assert!(least([0.1, f64::NAN]).is_nan());
        assert!(worst(std::iter::empty()).is_nan(), "nothing measured is no pass");
        assert_eq!(worst([f64::INFINITY, 1.0]), f64::INFINITY);
        // What f64::max does instead: the NaN is gone.
        assert_eq!([0.1, f64::NAN].into_iter().fold(0.0, f64::max), 0.1);
    }

    #[test]
    fn a_tolerance_knows_its_name_and_its_room() {
        assert_eq!(ERROR.name, "engine/bounds/src/lib.rs: ERROR");
        assert_eq!((ERROR.kind, ERROR.limit, ERROR.measured, ERROR.wider), (Kind::AtMost, 0.05, 0.03, None));
        assert!((ERROR.room() - 5.0 / 3.0).abs() < 1e-12);
        assert!((FLOOR.room() - 1.6).abs() < 1e-12 && FLOOR.wider == Some("a floor"));
        assert!((GAIN.room() - 1.5).abs() < 1e-12);
    }

    #[test]
    #[should_panic(expected = "2 failed:\nb is NaN")]
    fn assert_all_lists_every_failure() {
        assert_all([at_most("a", 1.0, 2.0), at_most("b", f64::NAN, 2.0), at_least("c", 1.0, 2.0)]);
    }
}
