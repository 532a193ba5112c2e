//! IESNA LM-63 photometric files (`.ies`) as headlamp intensity distributions.
//!
//! Read: the LM-63-1995 and LM-63-2002 layouts (and LM-63-1986/1991/2019 files, whose numbers
//! are laid out the same way), `TILT=NONE` and `TILT=INCLUDE` (the tilt block is skipped: a
//! headlamp does not tilt its lamp), photometric type C only. Types A and B are refused: their
//! axes differ, and a wrong guess would light the level wrongly without any error.
//!
//! Lamp frame: the photometric axis (vertical angle γ = 0, nadir) is the lamp's view direction,
//! −Z; horizontal angle C = 0 is the lamp's right (+X) and C = 90 its up (+Y), i.e. C turns
//! counter-clockwise as seen from behind the lamp, as LM-63 has it seen from above a luminaire
//! aiming down. Direction (γ, C) = (sin γ cos C, sin γ sin C, −cos γ).
//!
//! Only the shape is kept: T = candela / (largest candela in the file), so the level's `power`
//! is the W/sr of the brightest direction, as for the "spot" and "uniform" profiles. The
//! lumens, candela multiplier and ballast factor scale every value alike and so cancel out.

use std::path::Path;

use glam::Vec3;

use crate::distribution_image::DistributionImage;
use crate::error::{LoadError, LoadErrorKind, TextPos};
use crate::sources::Sources;

/// Largest .ies file read; real ones are tens of kilobytes.
pub const MAX_IES_BYTES: u64 = 16 << 20;
/// Most vertical or horizontal angles one file may declare (0.1° steps need 1801 and 3601).
pub const MAX_IES_ANGLES: usize = 4096;
/// Most candela values (vertical × horizontal angles) one file may declare.
pub const MAX_IES_VALUES: usize = 1 << 21;
/// Angle comparisons: files write 90 as "90", "90.0" or "90.00001".
const EPS_DEG: f32 = 1e-3;

/// How the horizontal angles a type C file gives cover the full turn (LM-63's symmetry rules).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Coverage {
    /// One angle, 0: the same in every plane.
    Rotational,
    /// 0..90: symmetric about the 0-180 and the 90-270 planes.
    Quadrant,
    /// 0..180: symmetric about the 0-180 plane.
    Half,
    /// 90..270: symmetric about the 90-270 plane.
    HalfFrom90,
    /// 0..360.
    Full,
}

/// A type C candela table, as in the file (the multiplier is not applied: only the shape is
/// used).
#[derive(Clone, Debug, PartialEq)]
pub struct IesProfile {
    /// γ, degrees from the photometric axis, increasing.
    vertical: Vec<f32>,
    /// C, degrees, increasing.
    horizontal: Vec<f32>,
    /// `candela[h * vertical.len() + v]`: the file's order, one horizontal angle after another.
    candela: Vec<f32>,
    coverage: Coverage,
    max: f32,
}

/// Reads `path` through `sources` (confined to the level folder, hashed) and parses it.
pub(crate) fn read_ies(path: &Path, sources: &mut Sources) -> Result<IesProfile, LoadError> {
    // Refuse a huge file before reading it all into memory.
    if let Ok(meta) = std::fs::metadata(path) {
        if meta.is_file() && meta.len() > MAX_IES_BYTES {
            return Err(LoadError::too_large(
                path,
                format!("IES file is {} bytes (limit {MAX_IES_BYTES})", meta.len()),
            ));
        }
    }
    let bytes = sources.read(path)?;
    IesProfile::parse(&bytes, path)
}

/// Texture side for a lamp of vertical field of view `fov_y`: 257, or more for wide lamps so
/// a texel stays within about 0.4° near the axis (steep, kinked tables then sample within 1 %),
/// capped at 513 because the renderer compares the whole texture every frame. Odd, so that
/// one texel centre lies on the axis, where most tables peak.
pub fn ies_texture_size(fov_y: f32) -> u32 {
    let wanted = 2.0 * (fov_y * 0.5).tan() / 0.4f32.to_radians();
    let size = if wanted.is_finite() { (wanted.ceil() as u32).clamp(256, 512) } else { 512 };
    size | 1
}

impl IesProfile {
    /// Parses LM-63 text. `path` only names the file in errors.
    pub fn parse(bytes: &[u8], path: &Path) -> Result<Self, LoadError> {
        Parser::new(bytes, path).profile()
    }

    /// The largest candela value in the file (as written, without the multiplier).
    pub fn max_candela(&self) -> f32 {
        self.max
    }

    /// Vertical angles γ as in the file, degrees.
    pub fn vertical_angles(&self) -> &[f32] {
        &self.vertical
    }

    /// Horizontal angles C as in the file, degrees.
    pub fn horizontal_angles(&self) -> &[f32] {
        &self.horizontal
    }

    /// Candela (file units) towards vertical angle `gamma` and horizontal angle `c`, degrees,
    /// bilinear in (γ, C) after LM-63's symmetry rules; 0 where the file's vertical angles do
    /// not reach.
    pub fn candela(&self, gamma: f32, c: f32) -> f32 {
        let (v_first, v_last) = (self.vertical[0], self.vertical[self.vertical.len() - 1]);
        if gamma.is_nan() || gamma < v_first - EPS_DEG || gamma > v_last + EPS_DEG {
            return 0.0;
        }
        let (v0, v1, tv) = segment(&self.vertical, gamma);
        let nv = self.vertical.len();
        let column = |h: usize| {
            let col = &self.candela[h * nv..(h + 1) * nv];
            col[v0] + (col[v1] - col[v0]) * tv
        };
        let (h0, h1, th) = segment(&self.horizontal, self.fold(c));
        let (a, b) = (column(h0), column(h1));
        a + (b - a) * th
    }

    /// Candela towards `dir` in the lamp frame (−Z the axis, +X C = 0, +Y C = 90).
    pub fn candela_towards(&self, dir: Vec3) -> f32 {
        let Some(d) = dir.try_normalize() else { return 0.0 };
        let gamma = (-d.z).clamp(-1.0, 1.0).acos().to_degrees();
        let c = d.y.atan2(d.x).to_degrees();
        self.candela(gamma, c)
    }

    /// T = candela / max over a lamp frustum of vertical FOV `fov_y` (radians) and `aspect`,
    /// `width` × `height` texels, top row first, each texel the direction through its centre
    /// as the renderer lays the texture over the frustum (engine/src/headlamp.rs).
    pub fn distribution(&self, fov_y: f32, aspect: f32, width: u32, height: u32) -> DistributionImage {
        let (tan_y, tan_x) = ((fov_y * 0.5).tan(), (fov_y * 0.5).tan() * aspect);
        let mut values = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                let ndc_x = (x as f32 + 0.5) / width as f32 * 2.0 - 1.0;
                let ndc_y = 1.0 - (y as f32 + 0.5) / height as f32 * 2.0;
                let t = self.candela_towards(Vec3::new(ndc_x * tan_x, ndc_y * tan_y, -1.0)) / self.max;
                values.push([t; 3]);
            }
        }
        DistributionImage { width, height, values }
    }

    /// Maps any C (degrees) into the range the file covers.
    fn fold(&self, c: f32) -> f32 {
        let c = c.rem_euclid(360.0);
        match self.coverage {
            Coverage::Rotational => 0.0,
            Coverage::Full => c,
            Coverage::Half => {
                if c > 180.0 {
                    360.0 - c
                } else {
                    c
                }
            }
            Coverage::Quadrant => {
                let c = if c > 180.0 { 360.0 - c } else { c };
                if c > 90.0 {
                    180.0 - c
                } else {
                    c
                }
            }
            Coverage::HalfFrom90 => {
                if c < 90.0 {
                    180.0 - c
                } else if c > 270.0 {
                    540.0 - c
                } else {
                    c
                }
            }
        }
    }
}

/// The two neighbouring entries of increasing `angles` around `x` and the weight of the
/// second; clamped to the ends. A single angle gives (0, 0, 0).
fn segment(angles: &[f32], x: f32) -> (usize, usize, f32) {
    if angles.len() < 2 {
        return (0, 0, 0.0);
    }
    let i = angles.partition_point(|&a| a <= x).clamp(1, angles.len() - 1) - 1;
    let t = ((x - angles[i]) / (angles[i + 1] - angles[i])).clamp(0.0, 1.0);
    (i, i + 1, t)
}

fn near(a: f32, b: f32) -> bool {
    (a - b).abs() <= EPS_DEG
}

/// One file's text; its errors name `path`.
struct Parser<'a> {
    path: &'a Path,
    text: String,
}

/// The line being split: its number, its text and the words left in it.
type Line<'t> = (usize, &'t str, std::str::Split<'t, fn(char) -> bool>);

/// The whitespace- (or comma-) separated tokens after the TILT line, wherever lines break
/// (tools wrap long rows freely), each with its place.
struct Tokens<'t> {
    lines: std::iter::Skip<std::iter::Enumerate<std::str::Lines<'t>>>,
    current: Option<Line<'t>>,
    /// Line of the last token handed out (for "the file ends after line N").
    last_line: usize,
}

/// Names a candela value in errors, formatted only when one is reported.
struct CandelaAt(f32, f32);

impl std::fmt::Display for CandelaAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "candela value at vertical angle {} of horizontal angle {}", self.0, self.1)
    }
}

fn separator(c: char) -> bool {
    c.is_whitespace() || c == ','
}

impl<'t> Iterator for Tokens<'t> {
    /// Where the token is, and the token.
    type Item = (TextPos, &'t str);
    fn next(&mut self) -> Option<Self::Item> {
        loop {
            if let Some((line, text, words)) = &mut self.current {
                if let Some(w) = words.find(|w| !w.is_empty()) {
                    self.last_line = *line;
                    // `w` is a slice of `text`: its byte offset gives the column.
                    let offset = w.as_ptr() as usize - text.as_ptr() as usize;
                    let column = text[..offset].chars().count() + 1;
                    return Some((TextPos { line: *line, column }, w));
                }
            }
            let (i, l) = self.lines.next()?;
            self.current = Some((i + 1, l, l.split(separator as fn(char) -> bool)));
        }
    }
}

impl<'a> Parser<'a> {
    fn new(bytes: &[u8], path: &'a Path) -> Self {
        // Header keywords are often Latin-1; only the numbers must be ASCII.
        Self { path, text: String::from_utf8_lossy(bytes).into_owned() }
    }

    /// An error placed at `at` (`path:line:column: ...`), or at a whole line.
    fn error(&self, at: Option<TextPos>, msg: impl std::fmt::Display) -> LoadError {
        LoadError::new(self.path, LoadErrorKind::InvalidLevel(format!("IES (LM-63) file: {msg}"))).at(at)
    }

    fn error_line(&self, line: usize, msg: impl std::fmt::Display) -> LoadError {
        self.error(Some(TextPos { line, column: 1 }), msg)
    }

    fn profile(&self) -> Result<IesProfile, LoadError> {
        let text = self.text.strip_prefix('\u{feff}').unwrap_or(&self.text);
        let (tilt_index, tilt) = text
            .lines()
            .enumerate()
            .find_map(|(i, l)| {
                let l = l.trim_start();
                let rest = l.get(..4).filter(|k| k.eq_ignore_ascii_case("TILT")).map(|_| l[4..].trim_start())?;
                rest.strip_prefix('=').map(|v| (i, v.trim()))
            })
            .ok_or_else(|| self.error(None, "no `TILT=` line: not an IESNA LM-63 photometric file"))?;
        let tilt_line = tilt_index + 1;
        let mut tokens =
            Tokens { lines: text.lines().enumerate().skip(tilt_line), current: None, last_line: tilt_line };

        if tilt.eq_ignore_ascii_case("INCLUDE") {
            self.skip_tilt(&mut tokens)?;
        } else if !tilt.eq_ignore_ascii_case("NONE") {
            return Err(self.error_line(
                tilt_line,
                format!("TILT={tilt}: tilt data in another file is not supported (use TILT=NONE or TILT=INCLUDE)"),
            ));
        }

        let _lamps = self.number(&mut tokens, "number of lamps")?;
        let _lumens = self.number(&mut tokens, "lumens per lamp")?;
        let (at, multiplier) = self.number_at(&mut tokens, &"candela multiplier")?;
        if multiplier <= 0.0 {
            return Err(self.error(Some(at), format!("candela multiplier ({multiplier}) must be greater than 0")));
        }
        let nv = self.count(&mut tokens, "number of vertical angles", 2)?;
        let nh = self.count(&mut tokens, "number of horizontal angles", 1)?;
        let (at, kind) = self.number_at(&mut tokens, &"photometric type")?;
        if kind == 2.0 || kind == 3.0 {
            let name = if kind == 2.0 { "B" } else { "A" };
            return Err(self.error(
                Some(at),
                format!("photometric type {name} ({kind}) is not supported; only type C (1) is read"),
            ));
        }
        if kind != 1.0 {
            return Err(self.error(Some(at), format!("photometric type {kind} is not 1 (C), 2 (B) or 3 (A)")));
        }
        if nv.saturating_mul(nh) > MAX_IES_VALUES {
            return Err(LoadError::too_large(
                self.path,
                format!("IES file declares {nv} × {nh} candela values (limit {MAX_IES_VALUES})"),
            ));
        }
        for what in ["units type", "width", "length", "height", "ballast factor", "ballast-lamp factor", "input watts"]
        {
            self.number(&mut tokens, what)?;
        }

        let vertical = self.angles(&mut tokens, nv, "vertical")?;
        let (first, last) = (vertical[0], vertical[nv - 1]);
        if !((near(first, 0.0) || near(first, 90.0)) && (near(last, 90.0) || near(last, 180.0))) {
            return Err(self.error_line(
                tokens.last_line,
                format!("type C vertical angles must run from 0 or 90 to 90 or 180, found {first} to {last}"),
            ));
        }
        let horizontal = self.angles(&mut tokens, nh, "horizontal")?;
        let (first, last) = (horizontal[0], horizontal[nh - 1]);
        let coverage = match (nh, first, last) {
            (1, f, _) if near(f, 0.0) => Coverage::Rotational,
            (_, f, l) if near(f, 0.0) && near(l, 90.0) => Coverage::Quadrant,
            (_, f, l) if near(f, 0.0) && near(l, 180.0) => Coverage::Half,
            (_, f, l) if near(f, 90.0) && near(l, 270.0) => Coverage::HalfFrom90,
            (_, f, l) if near(f, 0.0) && near(l, 360.0) => Coverage::Full,
            _ => {
                return Err(self.error_line(
                    tokens.last_line,
                    format!(
                        "type C horizontal angles must be 0, 0 to 90, 0 to 180, 90 to 270 or 0 to 360, \
                         found {first} to {last}"
                    ),
                ))
            }
        };

        let mut candela = Vec::with_capacity(nv * nh);
        for &h in &horizontal {
            for &v in &vertical {
                let what = CandelaAt(v, h);
                let (at, value) = self.number_at(&mut tokens, &what)?;
                if value < 0.0 {
                    return Err(self.error(Some(at), format!("{what} ({value}) is negative")));
                }
                candela.push(value);
            }
        }
        let max = candela.iter().copied().fold(0.0f32, f32::max);
        if max <= 0.0 {
            return Err(self.error(None, "every candela value is 0: the lamp would give no light"));
        }
        // Anything after the table (some tools append a blank line or a trailer) is ignored.
        Ok(IesProfile { vertical, horizontal, candela, coverage, max })
    }

    /// TILT=INCLUDE: lamp-to-luminaire geometry, N, N angles, N factors; checked and dropped.
    fn skip_tilt(&self, tokens: &mut Tokens) -> Result<(), LoadError> {
        self.number(tokens, "TILT=INCLUDE lamp-to-luminaire geometry")?;
        // Capped at MAX_IES_ANGLES like the other counts.
        let n = self.count(tokens, "number of tilt angles", 1)?;
        for i in 0..2 * n {
            let what = if i < n { "tilt angle" } else { "tilt multiplying factor" };
            self.number(tokens, what)?;
        }
        Ok(())
    }

    /// `n` angles, strictly increasing, within [0, 360].
    fn angles(&self, tokens: &mut Tokens, n: usize, kind: &str) -> Result<Vec<f32>, LoadError> {
        let mut angles: Vec<f32> = Vec::with_capacity(n);
        for i in 0..n {
            let (at, a) = self.number_at(tokens, &format_args!("{kind} angle {}", i + 1))?;
            if !(0.0..=360.0).contains(&a) {
                return Err(self.error(Some(at), format!("{kind} angle {a} is outside 0 to 360")));
            }
            if let Some(&prev) = angles.last() {
                if a <= prev {
                    return Err(self.error(Some(at), format!("{kind} angles must increase ({prev} then {a})")));
                }
            }
            angles.push(a);
        }
        Ok(angles)
    }

    /// A count of at least `min` and at most [`MAX_IES_ANGLES`].
    fn count(&self, tokens: &mut Tokens, what: &str, min: usize) -> Result<usize, LoadError> {
        let (at, v) = self.number_at(tokens, &what)?;
        if v.fract() != 0.0 || v < min as f32 {
            return Err(self.error(Some(at), format!("{what} ({v}) must be a whole number >= {min}")));
        }
        if v > MAX_IES_ANGLES as f32 {
            return Err(LoadError::too_large(self.path, format!("IES file: {what} is {v} (limit {MAX_IES_ANGLES})"))
                .at(Some(at)));
        }
        Ok(v as usize)
    }

    fn number(&self, tokens: &mut Tokens, what: &str) -> Result<f32, LoadError> {
        self.number_at(tokens, &what).map(|(_, v)| v)
    }

    /// The next token as a finite number, with its line. `what` is only formatted on error.
    fn number_at(&self, tokens: &mut Tokens, what: &dyn std::fmt::Display) -> Result<(TextPos, f32), LoadError> {
        let Some((at, token)) = tokens.next() else {
            return Err(self.error(None, format!("file ends after line {} while reading the {what}", tokens.last_line)));
        };
        match token.parse::<f32>() {
            Ok(v) if v.is_finite() => Ok((at, v)),
            _ => {
                let shown: String = token.chars().take(40).collect();
                Err(self.error(Some(at), format!("expected the {what} (a finite number), found `{shown}`")))
            }
        }
    }
}
