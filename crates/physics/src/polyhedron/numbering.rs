//! What a player reads off a die (docs/dice.md): the number on each face and where it is read.

use super::hull::Polyhedron;

/// Where a player reads a die that rests on a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReadAt {
    /// The face straight up, opposite the face down (every face has a parallel opposite one).
    TopFace,
    /// The number at the vertex straight up (the d4): a face's number is the one read while it
    /// is down, the label of the vertex it does not touch.
    TopVertex,
    /// The face down (a die whose faces have no parallel opposites, as an odd prism).
    BottomFace,
}

/// The numbers on a die's faces, in the order of its faces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Numbering {
    /// The number of each face (for [`ReadAt::TopVertex`], the number read with it down).
    pub numbers: Vec<u32>,
    pub read_at: ReadAt,
    /// The face whose normal is opposite each face's, where there is one.
    pub opposite: Vec<Option<usize>>,
}

impl Numbering {
    /// The number a player reads with `face` down.
    pub fn read_with_down(&self, face: usize) -> u32 {
        match (self.read_at, self.opposite[face]) {
            (ReadAt::TopFace, Some(up)) => self.numbers[up],
            _ => self.numbers[face],
        }
    }

    /// Faces in pairs of opposite faces summing to `N + 1` (`N` the number of faces), read at
    /// the top, then each number `n` written as `(n − 1 + first)·step`: the d8, d12 and d20
    /// (`first` 1, `step` 1), the d10 (0, 1) and the d% (0, 10). Going through the faces in
    /// their order, the `k`-th face not yet numbered gets `k + 1` for even `k` and `N − k` for
    /// odd `k`, so low and high numbers alternate around the die. `None` when a face has no
    /// opposite.
    pub fn in_opposite_pairs(shape: &Polyhedron, first: u32, step: u32) -> Option<Self> {
        let opposite = opposite_faces(shape);
        if opposite.iter().any(Option::is_none) {
            return None;
        }
        let count = shape.faces.len() as u32;
        let mut numbers = vec![0; shape.faces.len()];
        let mut k = 0;
        for face in 0..shape.faces.len() {
            if numbers[face] != 0 {
                continue;
            }
            let n = if k % 2 == 0 { k + 1 } else { count - k };
            numbers[face] = n;
            numbers[opposite[face]?] = count + 1 - n;
            k += 1;
        }
        let numbers = numbers.into_iter().map(|n| (n - 1 + first) * step).collect();
        Some(Self {
            numbers,
            read_at: ReadAt::TopFace,
            opposite,
        })
    }

    /// Any convex die: in opposite pairs read at the top when every face has an opposite one,
    /// else 1 to `N` in the faces' order, read at the face down.
    pub fn for_shape(shape: &Polyhedron) -> Self {
        Self::in_opposite_pairs(shape, 1, 1).unwrap_or_else(|| Self {
            numbers: (1..=shape.faces.len() as u32).collect(),
            read_at: ReadAt::BottomFace,
            opposite: opposite_faces(shape),
        })
    }
}

/// For each face, the face whose outward normal is opposite its own (to 10⁻⁹), if any.
pub fn opposite_faces(shape: &Polyhedron) -> Vec<Option<usize>> {
    shape
        .faces
        .iter()
        .map(|f| {
            shape
                .faces
                .iter()
                .position(|g| f.normal.dot(&g.normal) < -1.0 + 1e-9)
        })
        .collect()
}
