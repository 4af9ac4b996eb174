//! The stars of a set of triangles: which vertices (and, for the world
//! search, which edges) enough of them share, found by a counting pass
//! over a cheap hash before any map of the vertices.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

/// A cheap multiplicative hash (as rustc's `FxHasher`): the bucket counts
/// of [`Stars::new`], which only bound the exact counts, and maps of keys
/// hashed per pair, where SipHash cost more than the work it indexed
/// (`BuildHasherDefault<Mix>`). Not meant for keys chosen to collide.
#[derive(Clone, Copy, Debug, Default)]
pub struct Mix(u64);

impl Hasher for Mix {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        // Arrays of integers hash as one byte slice: eight bytes a step.
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            self.write_u64(u64::from_le_bytes(c.try_into().unwrap_or_default()));
        }
        for &b in chunks.remainder() {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x517c_c1b7_2722_0a95);
    }

    fn write_u32(&mut self, x: u32) {
        self.write_u64(u64::from(x));
    }

    fn write_i32(&mut self, x: i32) {
        self.write_u64(u64::from(x as u32));
    }

    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

/// What [`Stars::build`] is asked for.
#[derive(Clone, Copy, Default)]
struct Build {
    /// Only stars that pay for a search over pairs ([`Stars::paying`]).
    paying: bool,
    /// Books as stars of their own ([`Stars::paying_with_books`]).
    books: bool,
}

/// The maps of [`Stars::new`], on [`Mix`]: their keys are the few in full
/// buckets, but every corner is looked up.
type Map<K, V> = HashMap<K, V, BuildHasherDefault<Mix>>;

/// No star: the padding of [`Stars::stars_of`] and the group of a triangle in
/// no star.
pub const NO_STAR: u32 = u32::MAX;

/// The stars of a set of triangles: the vertices shared by at least a
/// given number of them (*hubs*), each with its triangles (*members*).
/// Pairs of members of one star are left to [`sector_pairs`](super::sector_pairs); everything
/// else to the caller's bins, which skip pairs sharing a hub.
#[derive(Clone, Debug, Default)]
pub struct Stars {
    /// Per triangle, the stars it belongs to, ascending, padded with
    /// [`NO_STAR`].
    of: Vec<[u32; 3]>,
    /// Where each star's members start in `members` (one more than the
    /// stars).
    start: Vec<usize>,
    /// Every star's members as (triangle, corner at the hub), star after
    /// star, triangles ascending.
    members: Vec<(u32, u8)>,
    /// Per star, whether it is a book ([`Stars::paying_with_books`]).
    book: Vec<bool>,
}

impl Stars {
    /// The stars of `n` triangles whose corners have the keys `corners(k)`
    /// (equal keys, equal points), with at least `min_members` triangles
    /// each. A triangle for which `corners` gives `None`, with two equal
    /// corner keys, or with an edge that `min_members` triangles share (a
    /// book's page), belongs to no star.
    pub fn new<K: Hash + Eq + Copy>(
        n: usize,
        corners: impl Fn(usize) -> Option<[K; 3]>,
        min_members: usize,
    ) -> Self {
        Self::build(n, corners, min_members, Build::default())
    }

    /// [`Stars::new`] when the stars pay for a search over the pairs of
    /// the `n` triangles ([`Stars::pay_for`]), else none, decided as early
    /// as the counts allow: a mesh whose only stars are the two poles of a
    /// UV sphere (`2 x 300` triangles among 180,000) costs one counting
    /// pass over its corners and no map of its vertices (`hider analyze
    /// gen:sphere:300` paid 9% for building stars it then dropped).
    pub fn paying<K: Hash + Eq + Copy>(
        n: usize,
        corners: impl Fn(usize) -> Option<[K; 3]>,
        min_members: usize,
    ) -> Self {
        let build = Build {
            paying: true,
            books: false,
        };
        Self::build(n, corners, min_members, build)
    }

    /// [`Stars::paying`], with every book a star of its own: an edge (the
    /// *spine*) that `min_members` triangles (its *pages*) share, whose
    /// members are the pages, each with the corner where the spine starts
    /// in it (the spine is that corner and the next). Two pages meet, if
    /// at all, along the spine, so a caller that can tell which pages may
    /// meet (by their angles around the spine) spares the bins' pairs;
    /// [`Stars::is_book`] tells books from stars around a vertex.
    pub fn paying_with_books<K: Hash + Eq + Copy>(
        n: usize,
        corners: impl Fn(usize) -> Option<[K; 3]>,
        min_members: usize,
    ) -> Self {
        let build = Build {
            paying: true,
            books: true,
        };
        Self::build(n, corners, min_members, build)
    }

    fn build<K: Hash + Eq + Copy>(
        n: usize,
        corners: impl Fn(usize) -> Option<[K; 3]>,
        min_members: usize,
        Build { paying, books }: Build,
    ) -> Self {
        // Keys are recomputed in each pass rather than stored: a stored
        // copy of every corner key cost 640 MB and a third of `hider
        // analyze gen:sphere:2000` (8 million triangles).
        let key_of = |k: usize| corners(k).filter(|c| c[0] != c[1] && c[1] != c[2] && c[0] != c[2]);
        let min = min_members.max(2);
        // Most vertices of most meshes have a handful of triangles: count
        // corners per bucket of a cheap hash first (a bucket holds at least
        // its keys' count), and count exactly only the keys of full
        // buckets, so that a mesh without stars costs no map of its
        // vertices (10% of `hider analyze gen:sphere:200` otherwise).
        // Four buckets a triangle: a mesh has about half a vertex a triangle,
        // so few buckets hold two of them.
        let bits = n.max(2).next_power_of_two().trailing_zeros() + 2;
        let bucket = |key: &K| {
            let mut h = Mix::default();
            key.hash(&mut h);
            (h.0 >> (64 - bits)) as usize
        };
        // 16 bits: a UV sphere's pole of 2,000 triangles is counted, not
        // saturated, so the bound below can settle it.
        let mut full = vec![0u16; 1 << bits];
        for c in (0..n).filter_map(key_of) {
            for key in &c {
                let b = &mut full[bucket(key)];
                *b = b.saturating_add(1);
            }
        }
        let is_full = |key: &K| usize::from(full[bucket(key)]) >= min;
        // The pairs inside stars are at most those of the full buckets
        // (`m^2 / 2` summed over a bucket's keys is at most that of their
        // sum); a saturated count bounds nothing.
        let within = |counts: &mut dyn Iterator<Item = usize>| {
            counts
                .filter(|&c| c >= min)
                .try_fold(0usize, |sum, c| {
                    (c < usize::from(u16::MAX)).then(|| sum.saturating_add(c * c / 2))
                })
                .unwrap_or(usize::MAX)
        };
        if within(&mut full.iter().map(|&c| usize::from(c))) <= if paying { n } else { 0 } {
            return Self::default();
        }
        // Book pages, once found.
        let mut excluded: Vec<bool> = Vec::new();
        let valences = |excluded: &[bool]| {
            let mut valence: Map<K, u32> = Map::default();
            for k in (0..n).filter(|&k| !excluded.get(k).copied().unwrap_or(false)) {
                let Some(c) = key_of(k) else { continue };
                for key in c.iter().filter(|k| is_full(k)) {
                    *valence.entry(*key).or_default() += 1;
                }
            }
            valence
        };
        let mut valence = valences(&excluded);
        // The bucket test first: most corners are in no full bucket, and
        // the map's look-up of every corner cost more than the bucket pass.
        let hub_key = |valence: &Map<K, u32>, key: &K| {
            is_full(key) && valence.get(key).is_some_and(|&v| v as usize >= min)
        };
        if within(&mut valence.values().map(|&v| v as usize)) <= if paying { n } else { 0 } {
            return Self::default();
        }
        // A book (many triangles around one edge) is a star at both ends of
        // the edge in which every pair shares the edge, and every pair's
        // sectors meet along it: the sectors would list them all. Its pages
        // are left to the caller's bins, as if there were no star.
        let spines = {
            let mut edges: Map<(K, K), u32> = Map::default();
            for c in (0..n).filter_map(key_of) {
                for i in 0..3 {
                    let (a, b) = (c[i], c[(i + 1) % 3]);
                    if hub_key(&valence, &a) && hub_key(&valence, &b) {
                        *edges.entry((a, b)).or_default() += 1;
                        *edges.entry((b, a)).or_default() += 1;
                    }
                }
            }
            edges.retain(|_, count| *count as usize >= min);
            edges
        };
        if !spines.is_empty() {
            excluded = (0..n)
                .map(|k| {
                    key_of(k).is_some_and(|c| {
                        (0..3).any(|i| spines.contains_key(&(c[i], c[(i + 1) % 3])))
                    })
                })
                .collect();
            valence = valences(&excluded);
        }
        // Hub ids in order of first appearance, so that they do not depend
        // on the hash order.
        let mut hub: Map<K, u32> = Map::default();
        let mut spine_hub: Map<(K, K), u32> = Map::default();
        let mut start = vec![0usize];
        let mut book = Vec::new();
        let mut of = vec![[NO_STAR; 3]; n];
        for (t, hubs) in of.iter_mut().enumerate() {
            let Some(c) = key_of(t) else { continue };
            let page = excluded.get(t).copied().unwrap_or(false);
            for i in 0..3 {
                let next = start.len() as u32 - 1;
                let h = if !page {
                    if !hub_key(&valence, &c[i]) {
                        continue;
                    }
                    *hub.entry(c[i]).or_insert(next)
                } else {
                    // A page: a member of each book whose spine it holds.
                    let (a, b) = (c[i], c[(i + 1) % 3]);
                    if !books || !spines.contains_key(&(a, b)) {
                        continue;
                    }
                    match spine_hub.get(&(b, a)) {
                        Some(&h) => h,
                        None => *spine_hub.entry((a, b)).or_insert(next),
                    }
                };
                if h == next {
                    start.push(0);
                    book.push(page);
                }
                start[h as usize + 1] += 1;
                hubs[i] = h;
            }
        }
        let stars = start.len() - 1;
        for h in 0..stars {
            start[h + 1] += start[h];
        }
        let mut fill = start.clone();
        let mut members = vec![(0u32, 0u8); start[stars]];
        for (t, hubs) in of.iter_mut().enumerate() {
            for (i, &h) in hubs.iter().enumerate() {
                if h != NO_STAR {
                    members[fill[h as usize]] = (t as u32, i as u8);
                    fill[h as usize] += 1;
                }
            }
            hubs.sort_unstable();
        }
        let stars = Self {
            of,
            start,
            members,
            book,
        };
        if paying && !stars.pay_for(n) {
            return Self::default();
        }
        stars
    }

    /// Whether star `h` is a book ([`Stars::paying_with_books`]): its
    /// members share an edge, not only a vertex.
    pub fn is_book(&self, h: usize) -> bool {
        self.book.get(h).copied().unwrap_or(false)
    }

    /// The number of stars.
    pub fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    /// Whether there is no star.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The members of star `h`: (triangle, corner at the hub), triangles
    /// ascending.
    pub fn members(&self, h: usize) -> &[(u32, u8)] {
        &self.members[self.start[h]..self.start[h + 1]]
    }

    /// The star a triangle's pairs are grouped under in bins: the first of
    /// its stars, or [`NO_STAR`].
    pub fn group(&self, t: usize) -> u32 {
        self.of.get(t).map_or(NO_STAR, |s| s[0])
    }

    /// The stars triangle `t` belongs to, ascending, padded with
    /// [`NO_STAR`].
    pub fn stars_of(&self, t: usize) -> [u32; 3] {
        self.of.get(t).copied().unwrap_or([NO_STAR; 3])
    }

    /// Whether the stars spare a search over the pairs of `n` triangles
    /// more than they cost it: the pairs inside stars (`m^2 / 2` for a star
    /// of `m`) outnumber the triangles. Grouping the bins by star and
    /// sorting the found pairs back into the bins' order is paid by every
    /// triangle, so the two poles of a UV sphere of 180,000 triangles (two
    /// stars of 300) are not worth it (+15% on `hider analyze
    /// gen:sphere:300`), while a fan of 1,000 is.
    pub fn pay_for(&self, n: usize) -> bool {
        let inside: usize = (0..self.len())
            .map(|h| {
                let m = self.members(h).len();
                m * m / 2
            })
            .sum();
        inside > n
    }

    /// Keeps the stars for which `keep(h)` holds, in order (renumbered);
    /// the triangles of the others belong to them no more.
    pub fn retain(&mut self, keep: impl Fn(usize) -> bool) {
        let mut renumber = vec![NO_STAR; self.len()];
        let mut start = vec![0usize];
        let mut members = Vec::new();
        let mut book = Vec::new();
        for (h, id) in renumber.iter_mut().enumerate() {
            if keep(h) {
                *id = start.len() as u32 - 1;
                members.extend_from_slice(self.members(h));
                start.push(members.len());
                book.push(self.is_book(h));
            }
        }
        for of in &mut self.of {
            for h in of.iter_mut().filter(|h| **h != NO_STAR) {
                *h = renumber[*h as usize];
            }
            of.sort_unstable();
        }
        self.start = start;
        self.members = members;
        self.book = book;
    }

    /// Whether triangles `a` and `b` belong to a common star (their pair
    /// is then one of [`sector_pairs`](super::sector_pairs)' of that star, not of the bins').
    pub fn share(&self, a: usize, b: usize) -> bool {
        let (Some(x), Some(y)) = (self.of.get(a), self.of.get(b)) else {
            return false;
        };
        x.iter().any(|&h| h != NO_STAR && y.contains(&h))
    }
}
