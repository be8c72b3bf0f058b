// A move-only owner of one Vulkan handle: destroys it with the function it was given, so
// every Vulkan object in the runtime is released exactly once, in reverse order of members.
#pragma once

#include <functional>
#include <utility>

namespace memograph::runtime {

template <typename T>
class VulkanHandle {
 public:
  VulkanHandle() = default;
  VulkanHandle(T handle, std::function<void(T)> destroy)
      : handle_(handle), destroy_(std::move(destroy)) {}
  VulkanHandle(const VulkanHandle&) = delete;
  VulkanHandle& operator=(const VulkanHandle&) = delete;
  VulkanHandle(VulkanHandle&& other) noexcept
      : handle_(std::exchange(other.handle_, T{})), destroy_(std::move(other.destroy_)) {}
  VulkanHandle& operator=(VulkanHandle&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, T{});
      destroy_ = std::move(other.destroy_);
    }
    return *this;
  }
  ~VulkanHandle() { reset(); }

  void reset() {
    if (handle_ != T{} && destroy_)
      destroy_(handle_);
    handle_ = T{};
  }
  T get() const { return handle_; }
  explicit operator bool() const { return handle_ != T{}; }

 private:
  T handle_{};
  std::function<void(T)> destroy_;
};

}  // namespace memograph::runtime
