// The exact state of a run as bytes, for checkpoints. Each component has one member
//   template <class Archive> void serialize(Archive& ar) { ar(a, b, c); }
// that serves both directions: writing appends the members' bytes, reading overwrites the members
// from them. Doubles travel as their bit patterns, so a restarted run continues bit for bit.
// Tags between components catch a reader that drifted out of step (a checkpoint from another
// version or another case) with a clear message instead of a silently wrong state.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "grainflow/core/error.hpp"

namespace grainflow::io {

class StateArchive {
 public:
  static StateArchive for_writing() { return StateArchive(false, {}, ""); }
  // `source` names the file in messages.
  static StateArchive for_reading(std::vector<std::uint8_t> bytes, std::string source) {
    return StateArchive(true, std::move(bytes), std::move(source));
  }

  bool loading() const { return loading_; }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

  template <class... T>
  void operator()(T&... values) {
    (item(values), ...);
  }

  // Writes `name`; reading checks that `name` comes next.
  void tag(const std::string& name) {
    std::string found = name;
    item(found);
    if (loading_ && found != name)
      throw RunError("checkpoint '" + source_ + "': expected the state of '" + name + "' but found '" + found +
                     "'; it was written by another version of grainflow or for another case");
  }

  // Reading: every byte was consumed.
  void expect_end() const {
    if (loading_ && cursor_ != bytes_.size())
      throw RunError("checkpoint '" + source_ + "' has " + std::to_string(bytes_.size() - cursor_) +
                     " bytes more than this case's state; it was written for another case or version");
  }

 private:
  StateArchive(bool loading, std::vector<std::uint8_t> bytes, std::string source)
      : loading_(loading), bytes_(std::move(bytes)), source_(std::move(source)) {}

  template <class T>
  static constexpr bool kPlain = std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>;

  template <class T>
  static constexpr bool has_serialize(int) requires requires(T& t, StateArchive& a) {
    t.serialize(a);
  }
  { return true; }
  template <class T>
  static constexpr bool has_serialize(long) {
    return false;
  }

  void raw(void* data, std::size_t size) {
    if (size == 0) return;
    if (loading_) {
      if (bytes_.size() - cursor_ < size)
        throw RunError("checkpoint '" + source_ + "' ends early; it is truncated or from another case or version");
      std::memcpy(data, bytes_.data() + cursor_, size);
      cursor_ += size;
    } else {
      const auto* p = static_cast<const std::uint8_t*>(data);
      bytes_.insert(bytes_.end(), p, p + size);
    }
  }

  std::size_t length(std::size_t n) {
    std::uint64_t size = n;
    raw(&size, sizeof size);
    if (loading_ && size > bytes_.size() - cursor_ + (1ull << 20))  // no element is < 0 bytes: bound before allocating
      throw RunError("checkpoint '" + source_ + "' is damaged: a length of " + std::to_string(size) + " elements");
    return static_cast<std::size_t>(size);
  }

  template <class T>
  void item(T& value) {
    if constexpr (has_serialize<T>(0)) {
      value.serialize(*this);
    } else if constexpr (kPlain<T>) {
      raw(&value, sizeof(T));
    } else {
      static_assert(sizeof(T) == 0, "StateArchive: give this type a serialize(Archive&) member");
    }
  }

  void item(std::string& s) {
    s.resize(length(s.size()));
    raw(s.data(), s.size());
  }

  template <class T, class A>
  void item(std::vector<T, A>& v) {
    static_assert(!std::is_same_v<T, bool>, "StateArchive: std::vector<bool> has no bytes to copy");
    v.resize(length(v.size()));
    if constexpr (kPlain<T> && !has_serialize<T>(0)) {
      raw(v.data(), v.size() * sizeof(T));
    } else {
      for (auto& x : v) item(x);
    }
  }

  template <class T, std::size_t N>
  void item(std::array<T, N>& a) {
    if constexpr (kPlain<T> && !has_serialize<T>(0)) raw(a.data(), sizeof a);
    else
      for (auto& x : a) item(x);
  }

  template <class T>
  void item(std::optional<T>& o) {
    bool present = o.has_value();
    raw(&present, sizeof present);
    if (loading_) {
      if (present && !o) o.emplace();
      if (!present) o.reset();
    }
    if (present) item(*o);
  }

  bool loading_;
  std::vector<std::uint8_t> bytes_;
  std::string source_;
  std::size_t cursor_ = 0;
};

}  // namespace grainflow::io
