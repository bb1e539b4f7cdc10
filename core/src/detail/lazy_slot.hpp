// A slot for an object made when first needed, like std::optional but without clearing its storage when the slot
// is made: libstdc++'s std::optional zero-fills its whole payload on default construction, and the simulator
// makes ~30 KB of such slots per run (modes, impact operators), a cost of its own in a fit's thousands of short
// runs. Not copyable or movable (the slots stay where their owner is). Internal to the simulator.
#pragma once

#include <new>
#include <utility>

namespace rockfit::core::detail {

template <class T>
class LazySlot {
 public:
  LazySlot() noexcept {}  // storage_ deliberately left uninitialised
  ~LazySlot() { reset(); }
  LazySlot(const LazySlot&) = delete;
  LazySlot& operator=(const LazySlot&) = delete;

  explicit operator bool() const { return engaged_; }
  bool has_value() const { return engaged_; }
  T& operator*() { return *get(); }
  const T& operator*() const { return *get(); }
  T* operator->() { return get(); }
  const T* operator->() const { return get(); }

  // Makes the object from `args` (ending the one there was).
  template <class... Args>
  T& emplace(Args&&... args) {
    reset();
    ::new (static_cast<void*>(storage_)) T(std::forward<Args>(args)...);
    engaged_ = true;
    return *get();
  }
  // The slot takes `value` (as std::optional's assignment from a value).
  LazySlot& operator=(T&& value) {
    if (engaged_) {
      *get() = std::move(value);
    } else {
      emplace(std::move(value));
    }
    return *this;
  }
  void reset() {
    if (engaged_) get()->~T();
    engaged_ = false;
  }

 private:
  T* get() { return std::launder(reinterpret_cast<T*>(storage_)); }
  const T* get() const { return std::launder(reinterpret_cast<const T*>(storage_)); }

  alignas(T) unsigned char storage_[sizeof(T)];
  bool engaged_ = false;
};

}  // namespace rockfit::core::detail
