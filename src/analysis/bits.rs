//! Small sets of keyword-set indices, and a union-find over keyword sets.

/// A set of keyword-set indices (a bit set).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub(crate) struct Bits(Vec<u64>);

impl Bits {
    /// The set holding only `i`.
    pub fn single(i: usize) -> Bits {
        let mut b = Bits::default();
        b.insert(i);
        b
    }

    /// Adds `i`.
    pub fn insert(&mut self, i: usize) {
        let word = i / 64;
        if self.0.len() <= word {
            self.0.resize(word + 1, 0);
        }
        self.0[word] |= 1 << (i % 64);
    }

    /// Adds every member of `other`.
    pub fn union_with(&mut self, other: &Bits) {
        if self.0.len() < other.0.len() {
            self.0.resize(other.0.len(), 0);
        }
        for (a, b) in self.0.iter_mut().zip(&other.0) {
            *a |= b;
        }
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.0.iter().all(|w| *w == 0)
    }

    /// The members, ascending.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.0.iter().enumerate().flat_map(|(w, &bits)| {
            (0..64)
                .filter(move |b| bits & (1 << b) != 0)
                .map(move |b| w * 64 + b)
        })
    }
}

/// Union-find over keyword-set indices.
#[derive(Clone, Debug)]
pub(crate) struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    /// The representative of `i`'s class: its smallest member.
    pub fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Merges the classes of `a` and `b`.
    pub fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            // The smaller root wins: every class is represented by its smallest member.
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            self.parent[hi] = lo;
        }
    }

    /// Merges every member of `bits` into one class; returns a member, if any.
    pub fn union_all(&mut self, bits: &Bits) -> Option<usize> {
        let mut members = bits.iter();
        let first = members.next()?;
        for m in members {
            self.union(first, m);
        }
        Some(first)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits_and_union_find() {
        let mut b = Bits::single(3);
        b.insert(70);
        b.union_with(&Bits::single(1));
        assert_eq!(b.iter().collect::<Vec<_>>(), vec![1, 3, 70]);
        assert!(!b.is_empty() && Bits::default().is_empty());
        let mut uf = UnionFind::new(71);
        uf.union(4, 2);
        assert_eq!(uf.union_all(&b), Some(1));
        assert_eq!(uf.find(4), uf.find(2));
        assert_eq!(uf.find(70), uf.find(3));
        assert_eq!(uf.find(3), 1, "the smallest index represents its class");
        assert_ne!(uf.find(0), uf.find(1));
        assert_eq!(uf.union_all(&Bits::default()), None);
    }
}
