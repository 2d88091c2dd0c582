//! Answers kept for repeated requests, by the SHA-256 of what was asked: the format, chart and
//! scale, the spec's text and every uploaded file's name and bytes. A spec that reads files under
//! the server's root also keeps each file's size and modification time; a change to either
//! makes the answer stale. The least recently used answers go first once the kept bytes pass the
//! cache's size.

use std::collections::{HashMap, VecDeque};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::SystemTime;

use sha2::{Digest, Sha256};

use super::job::Asked;
use super::reply::Reply;
use super::submitted::Submitted;

/// A request's hash.
pub type Key = [u8; 32];

/// A file under the root an answer was made from, as it was then.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Input {
    /// The file.
    pub path: PathBuf,
    /// Its size and modification time (`None` if they could not be read).
    pub stamp: Option<(u64, SystemTime)>,
}

impl Input {
    /// `path` as it is now.
    pub fn now(path: PathBuf) -> Input {
        let stamp = std::fs::metadata(&path).ok().and_then(|m| Some((m.len(), m.modified().ok()?)));
        Input { path, stamp }
    }

    fn unchanged(&self) -> bool {
        self.stamp.is_some() && Input::now(self.path.clone()) == *self
    }
}

/// The hash of what a request asks for.
pub fn key(asked: &Asked, submitted: &Submitted) -> Key {
    let mut hash = Sha256::new();
    let mut part = |bytes: &[u8]| {
        hash.update((bytes.len() as u64).to_le_bytes());
        hash.update(bytes);
    };
    part(b"dataink-serve-1");
    part(env!("CARGO_PKG_VERSION").as_bytes());
    part(asked.describe().as_bytes());
    part(submitted.spec.as_bytes());
    for (name, bytes) in &submitted.files {
        part(name.as_bytes());
        part(bytes);
    }
    hash.finalize().into()
}

struct Kept {
    reply: Reply,
    inputs: Vec<Input>,
}

#[derive(Default)]
struct Entries {
    by_key: HashMap<Key, Kept>,
    /// Keys from least to most recently used.
    order: VecDeque<Key>,
    bytes: usize,
}

/// The answers kept, up to a number of bytes.
pub struct Cache {
    limit: usize,
    entries: Mutex<Entries>,
}

impl Cache {
    /// An empty cache keeping up to `limit` bytes of answers.
    pub fn new(limit: usize) -> Cache {
        Cache { limit, entries: Mutex::new(Entries::default()) }
    }

    /// The answer kept for `key`, unless a file it was made from changed since.
    pub fn get(&self, key: &Key) -> Option<Reply> {
        let mut entries = self.entries.lock().ok()?;
        let fresh = entries.by_key.get(key).map(|kept| kept.inputs.iter().all(Input::unchanged))?;
        if !fresh {
            entries.remove(key);
            return None;
        }
        entries.touch(key);
        entries.by_key.get(key).map(|kept| kept.reply.clone())
    }

    /// Keep `reply` for `key`, made from `inputs`.
    pub fn put(&self, key: Key, reply: Reply, inputs: Vec<Input>) {
        let size = reply.body.len();
        if size > self.limit {
            return;
        }
        let Ok(mut entries) = self.entries.lock() else { return };
        entries.remove(&key);
        while entries.bytes + size > self.limit {
            let Some(oldest) = entries.order.front().copied() else { break };
            entries.remove(&oldest);
        }
        entries.bytes += size;
        entries.order.push_back(key);
        entries.by_key.insert(key, Kept { reply, inputs });
    }
}

impl Entries {
    fn remove(&mut self, key: &Key) {
        if let Some(kept) = self.by_key.remove(key) {
            self.bytes -= kept.reply.body.len();
            self.order.retain(|k| k != key);
        }
    }

    fn touch(&mut self, key: &Key) {
        self.order.retain(|k| k != key);
        self.order.push_back(*key);
    }
}

/// One turn per key: requests for the same answer made at once wait for the first to make it
/// (and then find it in the cache) instead of all making it.
#[derive(Default)]
pub struct Gates {
    by_key: Mutex<HashMap<Key, Arc<tokio::sync::Mutex<()>>>>,
}

/// A request's place at its key's gate; leaving (also when the request is dropped part way, as
/// when its client goes away) forgets the gate once nobody else holds it.
pub struct Entered<'a> {
    gates: &'a Gates,
    key: Key,
    gate: Option<Arc<tokio::sync::Mutex<()>>>,
}

impl Gates {
    /// Take a place at `key`'s gate, shared with every request for it now.
    pub fn enter(&self, key: &Key) -> Entered<'_> {
        let mut gates = self.by_key.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let gate = Arc::clone(gates.entry(*key).or_default());
        Entered { gates: self, key: *key, gate: Some(gate) }
    }

    /// Gates held now.
    pub fn len(&self) -> usize {
        self.by_key.lock().map_or(0, |g| g.len())
    }

    /// Whether no gate is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Entered<'_> {
    /// Wait for this key's turn (the gate is held until the place is dropped, so there always is
    /// one).
    pub async fn turn(&self) -> Option<tokio::sync::MutexGuard<'_, ()>> {
        match &self.gate {
            Some(gate) => Some(gate.lock().await),
            None => None,
        }
    }
}

impl Drop for Entered<'_> {
    fn drop(&mut self) {
        // References are taken and dropped only under the map's lock, so the count is exact.
        let mut gates = self.gates.by_key.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        drop(self.gate.take());
        if gates.get(&self.key).is_some_and(|g| Arc::strong_count(g) == 1) {
            gates.remove(&self.key);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reply(n: usize) -> Reply {
        Reply::ok("text/plain", vec![b'x'; n])
    }

    #[test]
    fn the_least_recently_used_answers_go_first() {
        let cache = Cache::new(250);
        cache.put([1; 32], reply(100), Vec::new());
        cache.put([2; 32], reply(100), Vec::new());
        assert!(cache.get(&[1; 32]).is_some(), "1 is now the most recent");
        cache.put([3; 32], reply(100), Vec::new());
        assert!(cache.get(&[2; 32]).is_none(), "2 was the least recent and made room");
        assert!(cache.get(&[1; 32]).is_some() && cache.get(&[3; 32]).is_some());
        cache.put([4; 32], reply(300), Vec::new());
        assert!(cache.get(&[4; 32]).is_none(), "an answer larger than the cache is not kept");
    }

    #[test]
    fn a_gate_is_forgotten_when_its_last_holder_leaves() {
        let gates = Gates::default();
        let first = gates.enter(&[1; 32]);
        let second = gates.enter(&[1; 32]);
        let other = gates.enter(&[2; 32]);
        assert_eq!(gates.len(), 2);
        drop(first);
        assert_eq!(gates.len(), 2, "the second request still holds key 1");
        drop(second);
        drop(other);
        assert!(gates.is_empty());
    }

    #[test]
    fn an_answer_goes_stale_when_its_file_changes() {
        let dir = std::env::temp_dir().join(format!("dataink-cache-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("d.csv");
        std::fs::write(&file, "a\n1\n").unwrap();
        let cache = Cache::new(1000);
        cache.put([7; 32], reply(10), vec![Input::now(file.clone())]);
        assert!(cache.get(&[7; 32]).is_some());
        std::fs::write(&file, "a\n1\n2\n").unwrap();
        assert!(cache.get(&[7; 32]).is_none(), "the file grew");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
