//! The adaptive volumetric shadow map's curve on the CPU (Salvi, Vidimce, Lauritzen and
//! Lefohn, EGSR 2010, section 3): per texel, transmittance against depth as a few nodes,
//! each the depth of a crossing and the light left past it. A crossing is inserted in depth
//! order; when the curve is full, the interior node whose removal changes the area under the
//! curve least goes, and the others keep their values (no refit), so the light left behind
//! the medium stays exact. `shaders/avsm_build.frag` does the same per texel in the same
//! float operations, and `shaders/lib/avsm.glsl` looks it up as [`Curve::lookup`] does.

/// One node: a depth and the transmittance from there on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    pub depth: f32,
    pub transmittance: f32,
}

/// A curve of at most `capacity` nodes, nearest first.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    nodes: Vec<Node>,
    capacity: usize,
}

impl Curve {
    /// An empty curve (all light left at every depth) of `capacity` nodes, at least 2: the
    /// first and the last are always kept.
    pub fn new(capacity: usize) -> Curve {
        assert!(capacity >= 2, "an AVSM curve keeps at least two nodes");
        Curve {
            nodes: Vec::with_capacity(capacity + 1),
            capacity,
        }
    }

    /// The curve of `crossings` (depth, opacity) inserted in the order given.
    pub fn from_crossings(
        capacity: usize,
        crossings: impl IntoIterator<Item = (f32, f32)>,
    ) -> Curve {
        let mut curve = Curve::new(capacity);
        for (depth, opacity) in crossings {
            curve.insert(depth, opacity);
        }
        curve
    }

    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Inserts a crossing at `depth` that lets (1 - `opacity`) through: a node with the
    /// curve's value there times that, after any node at the same depth; every node behind
    /// it is multiplied by it too. Then, if over capacity, drops one node ([`Self::compress`]).
    pub fn insert(&mut self, depth: f32, opacity: f32) {
        let pass = 1.0 - opacity.clamp(0.0, 1.0);
        let at = self.nodes.partition_point(|n| n.depth <= depth);
        let before = self.lookup(depth);
        self.nodes.insert(
            at,
            Node {
                depth,
                transmittance: before * pass,
            },
        );
        for n in &mut self.nodes[at + 1..] {
            n.transmittance *= pass;
        }
        if self.nodes.len() > self.capacity {
            self.compress();
        }
    }

    /// Drops the interior node whose removal changes the area under the curve least (the
    /// triangle it makes with its neighbours; the nearest on a tie).
    fn compress(&mut self) {
        let n = &self.nodes;
        let drop = (1..n.len() - 1)
            .map(|i| (i, removal_area(n[i - 1], n[i], n[i + 1])))
            .fold(None, |best: Option<(usize, f32)>, (i, a)| match best {
                Some((_, b)) if b <= a => best,
                _ => Some((i, a)),
            });
        if let Some((i, _)) = drop {
            self.nodes.remove(i);
        }
    }

    /// The light left at `depth`: 1 before the first node, linear between two nodes, the last
    /// node's value past it.
    pub fn lookup(&self, depth: f32) -> f32 {
        let n = &self.nodes;
        let i = n.partition_point(|n| n.depth <= depth);
        if i == 0 {
            return 1.0;
        }
        let a = n[i - 1];
        match n.get(i) {
            None => a.transmittance,
            Some(b) => {
                let w = (depth - a.depth) / (b.depth - a.depth);
                a.transmittance + (b.transmittance - a.transmittance) * w
            }
        }
    }
}

/// The area between the curve through `a`, `m`, `b` and the one straight from `a` to `b`.
pub fn removal_area(a: Node, m: Node, b: Node) -> f32 {
    let cross = (m.depth - a.depth) * (b.transmittance - a.transmittance)
        - (b.depth - a.depth) * (m.transmittance - a.transmittance);
    0.5 * cross.abs()
}

/// The exact curve of `crossings` sorted by depth: 1 before the first, the product of
/// (1 - opacity) over those at or before `depth`.
pub fn exact(crossings: &[(f32, f32)], depth: f32) -> f32 {
    crossings
        .iter()
        .filter(|(d, _)| *d <= depth)
        .map(|(_, a)| 1.0 - a)
        .product()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift), so the clouds are the same every run.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    /// `count` crossings in depth order in (0.1, 0.9), each of opacity in (0.05, 0.35).
    fn cloud(rng: &mut Rng, count: usize) -> Vec<(f32, f32)> {
        let mut c: Vec<(f32, f32)> = (0..count)
            .map(|_| (0.1 + 0.8 * rng.next(), 0.05 + 0.3 * rng.next()))
            .collect();
        c.sort_by(|a, b| a.0.total_cmp(&b.0));
        c
    }

    #[test]
    fn a_curve_that_fits_holds_every_crossing_exactly() {
        let crossings = [(0.2, 0.5), (0.3, 0.25), (0.5, 0.1), (0.7, 0.4)];
        let curve = Curve::from_crossings(4, crossings);
        let mut left = 1.0;
        assert_eq!(curve.nodes().len(), 4);
        for (node, (d, a)) in curve.nodes().iter().zip(crossings) {
            left *= 1.0 - a;
            assert_eq!(node.depth, d);
            assert!((node.transmittance - left).abs() < 1e-7, "{curve:?}");
            assert!((curve.lookup(d) - exact(&crossings, d)).abs() < 1e-7);
        }
        assert_eq!(curve.lookup(0.1), 1.0);
    }

    #[test]
    fn behind_the_medium_the_curve_is_exact_however_few_its_nodes() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for count in [5, 12, 40] {
            let crossings = cloud(&mut rng, count);
            let product: f32 = crossings.iter().map(|(_, a)| 1.0 - a).product();
            for n in [2, 4, 8] {
                let curve = Curve::from_crossings(n, crossings.iter().copied());
                assert_eq!(curve.nodes().len(), n.min(count));
                let behind = curve.lookup(0.95);
                assert!((behind - product).abs() < 1e-6, "{n}: {behind} {product}");
                // The first crossing's node is never dropped.
                assert_eq!(curve.nodes()[0].depth, crossings[0].0);
            }
        }
    }

    #[test]
    fn compression_drops_the_node_that_changes_the_area_least() {
        // The middle of three nodes on a straight line costs nothing; the one at 0.4 is
        // a sharp step, and stays.
        let mut curve = Curve::from_crossings(3, [(0.1, 0.5), (0.4, 0.5), (0.8, 0.0)]);
        curve.insert(0.9, 0.0);
        let depths: Vec<f32> = curve.nodes().iter().map(|n| n.depth).collect();
        assert_eq!(depths, [0.1, 0.4, 0.9]);
        let area = removal_area(curve.nodes()[0], curve.nodes()[1], curve.nodes()[2]);
        // Half of |0.3 x (0.25 - 0.5) - 0.8 x (0.25 - 0.5)|.
        assert!((area - 0.0625).abs() < 1e-7, "{area}");
    }

    /// Mean |curve - exact| over depths spread through the medium, averaged over clouds.
    fn mean_error(n: usize, clouds: &[Vec<(f32, f32)>]) -> f32 {
        let mut sum = 0.0;
        let steps = 200;
        for c in clouds {
            let curve = Curve::from_crossings(n, c.iter().copied());
            for k in 0..steps {
                let z = k as f32 / steps as f32;
                sum += (curve.lookup(z) - exact(c, z)).abs();
            }
        }
        sum / (steps * clouds.len()) as f32
    }

    #[test]
    fn the_error_against_the_exact_curve_falls_as_nodes_are_added() {
        let mut rng = Rng(12345);
        let clouds: Vec<_> = (0..50).map(|_| cloud(&mut rng, 32)).collect();
        let errors: Vec<f32> = [2, 4, 8, 16, 32].map(|n| mean_error(n, &clouds)).to_vec();
        println!("AVSM-2/4/8/16/32 against 32 crossings, mean error {errors:?}");
        for w in errors.windows(2) {
            assert!(w[1] < w[0], "{errors:?}");
        }
        // Linear between the nodes, even the lossless curve smears each step over the gap
        // before it; 8 nodes stay within a few hundredths of the exact curve.
        assert!(errors[2] < 0.05, "{errors:?}");
    }

    #[test]
    fn out_of_order_insertion_scales_the_nodes_behind() {
        let a = Curve::from_crossings(8, [(0.2, 0.5), (0.6, 0.5)]);
        let b = Curve::from_crossings(8, [(0.6, 0.5), (0.2, 0.5)]);
        assert_eq!(a, b);
        // Once compressed, the order shows.
        let c = cloud(&mut Rng(7), 12);
        let sorted = Curve::from_crossings(4, c.iter().copied());
        let reversed = Curve::from_crossings(4, c.iter().rev().copied());
        assert!((sorted.lookup(0.95) - reversed.lookup(0.95)).abs() < 1e-6);
        assert_ne!(sorted.nodes(), reversed.nodes());
    }
}
