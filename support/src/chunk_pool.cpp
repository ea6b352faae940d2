// The process's pool of kept chunks and the per-owner arenas carved from them (chunk_pool.hpp).
#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/kept_vector.hpp>
#include <panelrad/support/large_buffer.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>

namespace panelrad {

namespace {

constexpr std::size_t kAlignment = 64;

std::size_t round_up(std::size_t bytes, std::size_t unit) { return (bytes + unit - 1) / unit * unit; }

}  // namespace

ChunkPool& ChunkPool::process() {
  // Never destroyed: owners may outlive statics.
  static ChunkPool* const pool = new ChunkPool(default_limit(available_memory_bytes()));
  return *pool;
}

std::size_t ChunkPool::default_limit(std::size_t available) {
  if (available >= std::numeric_limits<std::size_t>::max() / 4) return kMinDefaultLimit;
  return std::max(kMinDefaultLimit, available / 16 / kChunkBytes * kChunkBytes);
}

ChunkPool::~ChunkPool() { release(); }

ChunkPool::Chunk ChunkPool::acquire(std::size_t bytes) {
  if (bytes > std::size_t{1} << 62) throw std::bad_alloc();
  const std::size_t wanted = round_up(std::max<std::size_t>(bytes, 1), kChunkBytes);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto best = fitting(wanted);
    if (best != kept_.end()) {
      const Chunk chunk = *best;
      kept_[static_cast<std::size_t>(best - kept_.cbegin())] = kept_.back();
      kept_.pop_back();
      kept_bytes_ -= chunk.bytes;
      return chunk;
    }
  }
  try {
    return {static_cast<std::byte*>(large_buffer_detail::allocate(wanted)), wanted};
  } catch (const std::bad_alloc&) {
    release();  // the kept chunks (none large enough) may be what stands in the way
    return {static_cast<std::byte*>(large_buffer_detail::allocate(wanted)), wanted};
  }
}

std::vector<ChunkPool::Chunk>::const_iterator ChunkPool::fitting(std::size_t wanted) const {
  auto best = kept_.cend();
  for (auto it = kept_.cbegin(); it != kept_.cend(); ++it)
    if (it->bytes >= wanted && it->bytes - wanted <= std::max(wanted, kChunkBytes) &&
        (best == kept_.cend() || it->bytes < best->bytes))
      best = it;
  return best;
}

std::size_t ChunkPool::kept_for(std::size_t bytes) const {
  if (bytes > std::size_t{1} << 62) return 0;
  const std::size_t wanted = round_up(std::max<std::size_t>(bytes, 1), kChunkBytes);
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto best = fitting(wanted);
  return best == kept_.cend() ? 0 : best->bytes;
}

void ChunkPool::give_back(Chunk chunk) noexcept {
  if (!chunk.data) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (kept_bytes_ + chunk.bytes <= limit_) {
      try {
        kept_.push_back(chunk);
        kept_bytes_ += chunk.bytes;
        return;
      } catch (const std::bad_alloc&) {
        // not kept: freed below
      }
    }
  }
  large_buffer_detail::release(chunk.data);
}

void ChunkPool::release() noexcept {
  const std::lock_guard<std::mutex> lock(mutex_);
  trim_to(0);
}

std::vector<ChunkPool::Chunk> ChunkPool::take_kept() {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Chunk> taken;
  taken.swap(kept_);
  kept_bytes_ = 0;
  return taken;
}

void ChunkPool::trim_to(std::size_t bytes) noexcept {
  while (kept_bytes_ > bytes && !kept_.empty()) {
    kept_bytes_ -= kept_.back().bytes;
    large_buffer_detail::release(kept_.back().data);
    kept_.pop_back();
  }
}

std::size_t ChunkPool::kept_bytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return kept_bytes_;
}

std::size_t ChunkPool::limit() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return limit_;
}

void ChunkPool::set_limit(std::size_t bytes) {
  const std::lock_guard<std::mutex> lock(mutex_);
  limit_ = bytes;
  trim_to(bytes);
}

ChunkArena::ChunkArena(int slots, ChunkPool& pool) { reset(slots, pool); }

void ChunkArena::reset(int slots, ChunkPool& pool) {
  if (slots < 1) throw std::invalid_argument("ChunkArena: " + std::to_string(slots) + " slots (at least 1)");
  clear();
  slots_.clear();
  slots_.resize(static_cast<std::size_t>(slots));
  pool_ = &pool;
}

std::byte* ChunkArena::allocate(int slot, std::size_t bytes) {
  if (slot < 0 || static_cast<std::size_t>(slot) >= slots_.size())
    throw std::out_of_range("ChunkArena::allocate: slot " + std::to_string(slot) + " of " +
                            std::to_string(slots_.size()));
  Slot& s = slots_[static_cast<std::size_t>(slot)];
  const std::size_t size = round_up(std::max<std::size_t>(bytes, 1), kAlignment);
  if (s.chunks.empty() || s.chunks.back().bytes - s.used < size) {
    s.chunks.reserve(s.chunks.size() + 1);  // before the chunk is taken: a throw here loses none
    s.chunks.push_back(pool_->acquire(size));
    s.used = 0;
  }
  std::byte* p = s.chunks.back().data + s.used;
  s.used += size;
  return p;
}

void ChunkArena::clear() noexcept {
  for (Slot& s : slots_) {
    for (const ChunkPool::Chunk& c : s.chunks) pool_->give_back(c);
    s.chunks.clear();
    s.used = 0;
  }
}

std::size_t ChunkArena::chunk_bytes() const {
  std::size_t bytes = 0;
  for (const Slot& s : slots_)
    for (const ChunkPool::Chunk& c : s.chunks) bytes += c.bytes;
  return bytes;
}

namespace kept_detail {

// A kept array's chunk: the chunk's size in its first 64 bytes (the header), the array after it.
constexpr std::size_t kHeader = 64;

void* acquire(std::size_t bytes) {
  if (bytes > std::numeric_limits<std::size_t>::max() - kHeader) throw std::bad_alloc();
  const ChunkPool::Chunk chunk = ChunkPool::process().acquire(bytes + kHeader);
  std::memcpy(chunk.data, &chunk.bytes, sizeof chunk.bytes);
  return chunk.data + kHeader;
}

void give_back(void* p) noexcept {
  if (!p) return;
  ChunkPool::Chunk chunk;
  chunk.data = static_cast<std::byte*>(p) - kHeader;
  std::memcpy(&chunk.bytes, chunk.data, sizeof chunk.bytes);
  ChunkPool::process().give_back(chunk);
}

}  // namespace kept_detail

}  // namespace panelrad
