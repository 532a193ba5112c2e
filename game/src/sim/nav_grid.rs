//! Where a crawler can walk, as a grid of floor cells built once from the level's collision
//! geometry, and the way from one cell to another by breadth-first search. Crawlers go
//! straight at what they can see; the grid takes them round walls and through doorways to
//! what they cannot.
//!
//! One floor per (x, z) column: a cell's floor is the first walkable surface below a probe
//! from [`PROBE_HEIGHT`] above the level's lowest point, so levels with rooms stacked over
//! each other are walked on their lowest storey only.

use glam::Vec3;
use physics::LevelCollision;

/// Cell size, m: below a crawler's width, so a 1.4 m doorway is at least two cells wide.
pub const CELL: f32 = 0.5;
/// A bigger level gets bigger cells, so building the grid stays quick (each cell is a ray and
/// a shape query); narrow doorways may then close for crawlers.
pub const MAX_CELLS: usize = 100_000;
/// Probes start this far above the level's lowest point, m.
pub const PROBE_HEIGHT: f32 = 2.0;
/// Neighbouring floors further apart in height than this are not connected, m.
const MAX_STEP: f32 = 0.36;
/// The body is tested this far above the floor, so low steps and the floor itself do not
/// count as obstacles, m.
const CLEARANCE: f32 = 0.3;

pub struct NavGrid {
    /// Edge of a cell, m.
    cell: f32,
    /// World x, z of cell (0, 0)'s centre.
    origin: (f32, f32),
    width: usize,
    depth: usize,
    /// Floor height per cell, or None where a body does not fit.
    floor: Vec<Option<f32>>,
}

/// 8-connected: the 4 sides, then the 4 diagonals (taken only when both sides beside them are
/// open, so paths never cut a wall's corner).
const NEIGHBOURS: [(i32, i32); 8] = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)];

impl NavGrid {
    /// Cells where a capsule of `radius` and `height` stands on walkable floor.
    pub fn build(level: &LevelCollision, radius: f32, height: f32) -> Self {
        let (lo, hi) = level.bounds();
        let area = (hi.x - lo.x).max(CELL) * (hi.z - lo.z).max(CELL);
        let cell = CELL.max((area / MAX_CELLS as f32).sqrt());
        let width = (((hi.x - lo.x) / cell).ceil() as usize).max(1);
        let depth = (((hi.z - lo.z) / cell).ceil() as usize).max(1);
        let origin = (lo.x + 0.5 * cell, lo.z + 0.5 * cell);
        let top = lo.y + PROBE_HEIGHT;
        let mut floor = Vec::with_capacity(width * depth);
        for j in 0..depth {
            for i in 0..width {
                let (x, z) = (origin.0 + i as f32 * cell, origin.1 + j as f32 * cell);
                let ground = level.cast_ray(Vec3::new(x, top, z), -Vec3::Y, PROBE_HEIGHT + 1.0);
                let cell = ground.filter(|g| g.normal.y >= 0.7).map(|g| g.point.y).filter(|&y| {
                    level.capsule_fits(Vec3::new(x, y + CLEARANCE, z), radius, (height - CLEARANCE).max(2.0 * radius))
                });
                floor.push(cell);
            }
        }
        Self { cell, origin, width, depth, floor }
    }

    /// No walkable cell at all: every way is unknown.
    pub fn empty() -> Self {
        Self { cell: CELL, origin: (0.0, 0.0), width: 1, depth: 1, floor: vec![None] }
    }

    fn cell_of(&self, p: Vec3) -> Option<(usize, usize)> {
        let i = ((p.x - self.origin.0) / self.cell).round();
        let j = ((p.z - self.origin.1) / self.cell).round();
        (i >= 0.0 && j >= 0.0 && (i as usize) < self.width && (j as usize) < self.depth)
            .then_some((i as usize, j as usize))
    }

    fn centre(&self, (i, j): (usize, usize)) -> Vec3 {
        let y = self.floor[j * self.width + i].unwrap_or(0.0);
        Vec3::new(self.origin.0 + i as f32 * self.cell, y, self.origin.1 + j as f32 * self.cell)
    }

    pub fn walkable(&self, p: Vec3) -> bool {
        self.cell_of(p).is_some_and(|(i, j)| self.floor[j * self.width + i].is_some())
    }

    fn open(&self, i: i32, j: i32) -> Option<f32> {
        if i < 0 || j < 0 || i as usize >= self.width || j as usize >= self.depth {
            return None;
        }
        self.floor[j as usize * self.width + i as usize]
    }

    /// Whether one may walk from cell a to its neighbour (di, dj).
    fn passable(&self, i: i32, j: i32, di: i32, dj: i32) -> bool {
        let (Some(here), Some(there)) = (self.open(i, j), self.open(i + di, j + dj)) else { return false };
        let corner_clear = di == 0 || dj == 0 || (self.open(i + di, j).is_some() && self.open(i, j + dj).is_some());
        (here - there).abs() <= MAX_STEP && corner_clear
    }

    /// The next point to walk to on the shortest way from `from` to `to`: the centre of the
    /// neighbouring cell one step nearer. None when either end is off the grid or no way joins
    /// them. Ties go to the first neighbour in [`NEIGHBOURS`] order: deterministic.
    pub fn next_step(&self, from: Vec3, to: Vec3) -> Option<Vec3> {
        let start = self.nearest_open(self.cell_of(from)?)?;
        let goal = self.nearest_open(self.cell_of(to)?)?;
        let distance = self.steps_from(goal, Some(start));
        let index = |(i, j): (usize, usize)| j * self.width + i;
        let here = distance[index(start)];
        if here == u32::MAX {
            return None;
        }
        if here == 0 {
            return Some(to);
        }
        NEIGHBOURS
            .iter()
            .map(|&(di, dj)| (start.0 as i32 + di, start.1 as i32 + dj, di, dj))
            .filter(|&(_, _, di, dj)| self.passable(start.0 as i32, start.1 as i32, di, dj))
            .map(|(i, j, _, _)| (i as usize, j as usize))
            .find(|&c| distance[index(c)] == here - 1)
            .map(|c| self.centre(c))
    }

    /// Every cell one can walk to from `from` (with no open cell there, or off the grid: None).
    pub fn reachable_from(&self, from: Vec3) -> Option<Reachable<'_>> {
        let start = self.nearest_open(self.cell_of(from)?)?;
        Some(Reachable { grid: self, steps: self.steps_from(start, None) })
    }

    /// Steps from `goal` to every cell, breadth-first (diagonals cost the same as sides, which
    /// keeps it a BFS; a crawler steers straight once it can see its target anyway), stopping
    /// once `until` is reached. u32::MAX: not reached.
    fn steps_from(&self, goal: (usize, usize), until: Option<(usize, usize)>) -> Vec<u32> {
        let mut distance = vec![u32::MAX; self.floor.len()];
        let index = |(i, j): (usize, usize)| j * self.width + i;
        let mut queue = std::collections::VecDeque::from([goal]);
        distance[index(goal)] = 0;
        while let Some((i, j)) = queue.pop_front() {
            if Some((i, j)) == until {
                break;
            }
            for (di, dj) in NEIGHBOURS {
                let (ni, nj) = (i as i32 + di, j as i32 + dj);
                if self.passable(i as i32, j as i32, di, dj) && distance[index((ni as usize, nj as usize))] == u32::MAX
                {
                    distance[index((ni as usize, nj as usize))] = distance[index((i, j))] + 1;
                    queue.push_back((ni as usize, nj as usize));
                }
            }
        }
        distance
    }

    /// The cell itself if open, else an open one of its neighbours (a body pressed against a
    /// wall can have its centre in a blocked cell).
    fn nearest_open(&self, (i, j): (usize, usize)) -> Option<(usize, usize)> {
        std::iter::once((0, 0))
            .chain(NEIGHBOURS)
            .map(|(di, dj)| (i as i32 + di, j as i32 + dj))
            .find(|&(a, b)| self.open(a, b).is_some())
            .map(|(a, b)| (a as usize, b as usize))
    }
}

/// The part of a [`NavGrid`] one can walk to from a starting point.
pub struct Reachable<'a> {
    grid: &'a NavGrid,
    steps: Vec<u32>,
}

impl Reachable<'_> {
    /// Whether `p` (its cell, or an open neighbour of it: a thing against a wall) is reached.
    pub fn contains(&self, p: Vec3) -> bool {
        let grid = self.grid;
        grid.cell_of(p)
            .and_then(|c| grid.nearest_open(c))
            .is_some_and(|(i, j)| self.steps[j * grid.width + i] != u32::MAX)
    }

    /// Whether some reached cell comes within `radius` of `p` horizontally (a body can stand
    /// anywhere in its cell, so half a cell's diagonal is allowed on top) with its floor within
    /// `height` of `p`: a thing on a crate, grabbed from beside it.
    pub fn comes_within(&self, p: Vec3, radius: f32, height: f32) -> bool {
        let grid = self.grid;
        let reach = radius + grid.cell * std::f32::consts::FRAC_1_SQRT_2;
        let cells = (reach / grid.cell).ceil() as i32 + 1;
        let (ci, cj) =
            (((p.x - grid.origin.0) / grid.cell).round() as i32, ((p.z - grid.origin.1) / grid.cell).round() as i32);
        (-cells..=cells).flat_map(|dj| (-cells..=cells).map(move |di| (ci + di, cj + dj))).any(|(i, j)| {
            let Some(floor) = grid.open(i, j) else { return false };
            let (x, z) = (grid.origin.0 + i as f32 * grid.cell, grid.origin.1 + j as f32 * grid.cell);
            let reached = self.steps[j as usize * grid.width + i as usize] != u32::MAX;
            reached && (x - p.x).hypot(z - p.z) <= reach && (floor - p.y).abs() <= height
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 10 m square room split by a wall along z = 0 with a 1.5 m gap at x ∈ [3, 4.5].
    fn room() -> LevelCollision {
        let mut p = vec![
            Vec3::new(-5.0, 0.0, -5.0),
            Vec3::new(5.0, 0.0, -5.0),
            Vec3::new(5.0, 0.0, 5.0),
            Vec3::new(-5.0, 0.0, 5.0),
        ];
        let mut t = vec![[0, 2, 1], [0, 3, 2]];
        for (x0, x1) in [(-5.0, 3.0), (4.5, 5.0)] {
            let b = p.len() as u32;
            p.extend([
                Vec3::new(x0, 0.0, 0.0),
                Vec3::new(x1, 0.0, 0.0),
                Vec3::new(x1, 3.0, 0.0),
                Vec3::new(x0, 3.0, 0.0),
            ]);
            t.extend([[b, b + 1, b + 2], [b, b + 2, b + 3]]);
        }
        LevelCollision::from_triangles(&p, &t).unwrap()
    }

    #[test]
    fn the_way_round_a_wall_goes_through_its_gap() {
        let level = room();
        let grid = NavGrid::build(&level, 0.35, 1.5);
        assert!(grid.walkable(Vec3::new(-2.0, 0.0, -2.0)));
        assert!(!grid.walkable(Vec3::new(-2.0, 0.0, 0.0)), "the wall");
        // Walk the grid's steps from one side to the other.
        let (mut at, goal) = (Vec3::new(-3.0, 0.0, -3.0), Vec3::new(-3.0, 0.0, 3.0));
        let mut through_gap = false;
        for _ in 0..100 {
            if at.distance(goal) < 0.1 {
                break;
            }
            at = grid.next_step(at, goal).expect("a way exists");
            through_gap |= at.z.abs() < 0.3 && (3.0..=4.5).contains(&at.x);
        }
        assert!(at.distance(goal) < 0.1 && through_gap, "ended at {at}");
    }

    #[test]
    fn a_huge_level_gets_bigger_cells() {
        let p = [
            Vec3::new(-2000.0, 0.0, -2000.0),
            Vec3::new(2000.0, 0.0, -2000.0),
            Vec3::new(2000.0, 0.0, 2000.0),
            Vec3::new(-2000.0, 0.0, 2000.0),
        ];
        let level = LevelCollision::from_triangles(&p, &[[0, 2, 1], [0, 3, 2]]).unwrap();
        let grid = NavGrid::build(&level, 0.35, 1.5);
        assert!(grid.floor.len() <= MAX_CELLS + 2 * 1000, "{} cells", grid.floor.len());
        assert!(grid.cell > CELL);
        let step = grid.next_step(Vec3::new(-100.0, 0.0, 0.0), Vec3::new(100.0, 0.0, 0.0)).unwrap();
        assert!(step.x > -100.0, "still leads the way: {step}");
        assert_eq!(NavGrid::empty().next_step(Vec3::ZERO, Vec3::X), None);
    }

    #[test]
    fn no_way_into_a_closed_room() {
        let level = room();
        let grid = NavGrid::build(&level, 1.9, 1.5);
        // Too wide for the gap.
        assert_eq!(grid.next_step(Vec3::new(-2.0, 0.0, -3.0), Vec3::new(-2.0, 0.0, 3.0)), None);
        let reach = grid.reachable_from(Vec3::new(-2.0, 0.0, -3.0)).unwrap();
        assert!(reach.contains(Vec3::new(2.0, 0.0, -3.0)) && !reach.contains(Vec3::new(-2.0, 0.0, 3.0)));
        let narrow = NavGrid::build(&level, 0.35, 1.5);
        let reach = narrow.reachable_from(Vec3::new(-2.0, 0.0, -3.0)).unwrap();
        assert!(reach.contains(Vec3::new(-2.0, 0.0, 3.0)), "the gap lets a narrow body through");
        assert_eq!(grid.next_step(Vec3::new(50.0, 0.0, 0.0), Vec3::ZERO), None, "off the grid");
    }
}
