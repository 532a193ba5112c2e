//! A top-down ASCII map of a level (north = -Z at the top), for eyeballing the layout.

use crate::geometry::Aabb;
use crate::layout::{Level, Shape, Solid, SolidKind};
use crate::materials::Material;

/// Metres per map cell; each cell is printed two characters wide so cells look square.
const CELL: f64 = 0.5;
const SUB: usize = 5;

fn wall_char(m: Material) -> char {
    match m {
        Material::White | Material::Plaster | Material::CellarPlaster => '#',
        Material::Red | Material::RedPlaster => 'R',
        Material::Green | Material::GreenTile | Material::GreenPlaster => 'G',
        Material::Blue | Material::BluePlaster => 'B',
        Material::Yellow | Material::YellowBrick => 'Y',
        Material::Concrete | Material::Stone | Material::FloorTile | Material::CellarConcrete | Material::WetStone => {
            '%'
        }
        Material::Wood | Material::Planks | Material::DarkPlanks | Material::VarnishedWood => 'w',
        Material::Steel | Material::Copper => 'm',
        Material::Brick => 'b',
    }
}

fn inside_xz(b: &Aabb, x: f64, z: f64) -> bool {
    x >= b.min[0] && x <= b.max[0] && z >= b.min[2] && z <= b.max[2]
}

pub fn ascii_map(level: &Level, solids: &[Solid]) -> String {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for r in &level.rooms {
        let s = r.shell();
        lo = [lo[0].min(s.min[0]), lo[1].min(s.min[2])];
        hi = [hi[0].max(s.max[0]), hi[1].max(s.max[2])];
    }
    let cols = ((hi[0] - lo[0]) / CELL).ceil() as usize;
    let rows = ((hi[1] - lo[1]) / CELL).ceil() as usize;
    let mut grid = vec![vec![[' ', ' ']; cols]; rows];

    for (row, line) in grid.iter_mut().enumerate() {
        for (col, cell) in line.iter_mut().enumerate() {
            let (x0, z0) = (lo[0] + col as f64 * CELL, lo[1] + row as f64 * CELL);
            let samples: Vec<(f64, f64)> = (0..SUB * SUB)
                .map(|k| {
                    let (i, j) = ((k % SUB) as f64 + 0.5, (k / SUB) as f64 + 0.5);
                    (x0 + i * CELL / SUB as f64, z0 + j * CELL / SUB as f64)
                })
                .collect();
            // Walls at waist height, by the material with most samples.
            let mut counts = [0usize; Material::ALL.len()];
            for s in solids.iter().filter(|s| matches!(s.kind, SolidKind::Wall)) {
                let n = samples.iter().filter(|&&(x, z)| inside_xz(&s.bounds, x, z)).count();
                counts[s.material as usize] += n;
            }
            let best = (0..counts.len()).max_by_key(|&i| (counts[i], usize::MAX - i)).unwrap();
            if counts[best] > 0 {
                let c = wall_char(Material::ALL[best]);
                *cell = [c, c];
                continue;
            }
            let prop = level.props.iter().find(|p| {
                let b = p.shape.bounds();
                samples.iter().any(|&(x, z)| inside_xz(&b, x, z))
            });
            if let Some(p) = prop {
                let b = p.shape.bounds();
                *cell = match p.shape {
                    Shape::Ramp { .. } => ['/', '/'],
                    _ if b.size()[1] >= 5.0 => ['P', 'P'],
                    _ if b.size()[1] <= 0.5 => ['=', '='],
                    _ => ['x', 'x'],
                };
                continue;
            }
            let (cx, cz) = (x0 + 0.5 * CELL, z0 + 0.5 * CELL);
            let passage = level.resolved_doorways().iter().any(|d| inside_xz(&d.passage, cx, cz));
            if passage || level.rooms.iter().any(|r| inside_xz(&r.interior(), cx, cz)) {
                *cell = ['.', ' '];
            }
        }
    }

    let put = |grid: &mut Vec<Vec<[char; 2]>>, x: f64, z: f64, text: &str| {
        let row = ((z - lo[1]) / CELL).floor() as usize;
        let col = ((x - lo[0]) / CELL).floor() as usize;
        for (k, ch) in text.chars().enumerate() {
            let c = col * 2 + k;
            if row < rows && c / 2 < cols {
                grid[row][c / 2][c % 2] = ch;
            }
        }
    };
    for l in &level.lights {
        put(&mut grid, l.position[0], l.position[2], "*");
    }
    for m in &level.markers {
        let symbol = if m.extras.get("spawn").is_some() {
            "@"
        } else if m.extras.get("pickup").is_some() {
            "$"
        } else if m.extras.get("enemy").is_some() {
            "!"
        } else if m.extras.get("exit").is_some() {
            "X"
        } else if m.extras.get("waypoint").is_some() {
            "+"
        } else {
            "?"
        };
        put(&mut grid, m.position[0], m.position[2], symbol);
    }

    // Room names on the row nearest the room's centre where they only cover floor.
    for r in &level.rooms {
        let c = r.interior().center();
        let x = c[0] - 0.25 * CELL * r.name.len() as f64;
        let col = ((x - lo[0]) / CELL).floor() as usize;
        let centre_row = ((c[2] - lo[1]) / CELL).floor() as usize;
        let cells = r.name.len().div_ceil(2) + 1;
        let free = |row: usize| {
            row < rows && col + cells <= cols && grid[row][col..col + cells].iter().all(|cell| *cell == ['.', ' '])
        };
        // Only rows whose cells lie inside the room; a room too narrow for its name gets it on
        // the centre row, over its walls.
        let first = ((r.min[1] - lo[1]) / CELL).ceil() as usize;
        let last = ((r.max[1] - lo[1]) / CELL).floor() as usize;
        let row = (0..rows)
            .flat_map(|d| [centre_row + d, centre_row.wrapping_sub(d)])
            .filter(|row| (first..last).contains(row))
            .find(|&row| free(row))
            .unwrap_or(centre_row);
        put(&mut grid, x, lo[1] + (row as f64 + 0.5) * CELL, r.name);
    }
    let mut out = String::new();
    out.push_str(&format!(
        "{} — top-down, north (-Z) up, east (+X) right, 1 cell = {CELL} m, x {:.1}..{:.1}, z {:.1}..{:.1}\n",
        level.name, lo[0], hi[0], lo[1], hi[1]
    ));
    for line in &grid {
        let s: String = line.iter().flatten().collect();
        out.push_str(s.trim_end());
        out.push('\n');
    }
    out.push_str(
        "walls: # white  R red  G green  B blue  Y yellow  % concrete/stone  b brick   (gaps = doorways)\n\
         props: x crate/block  P pillar  = dais/step  / ramp     @ spawn  $ battery  ! crawler  * light\n",
    );
    out
}
