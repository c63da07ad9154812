// The move-only owner of one GL object name (Magnum's pattern): deleted copy, a noexcept move
// that zeroes the source, a destructor that deletes a non-zero name.
#pragma once

#include <utility>

namespace twinrender::realtime::gl {

class Handle {
  public:
    using Deleter = void (*)(unsigned id);

    Handle() = default;
    Handle(unsigned id, Deleter deleter) : mId(id), mDeleter(deleter) {}
    ~Handle() { reset(); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    Handle(Handle&& other) noexcept : mId(std::exchange(other.mId, 0u)), mDeleter(other.mDeleter) {}
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            mId = std::exchange(other.mId, 0u);
            mDeleter = other.mDeleter;
        }
        return *this;
    }

    unsigned id() const { return mId; }
    explicit operator bool() const { return mId != 0; }
    void reset() {
        if (mId != 0 && mDeleter) mDeleter(mId);
        mId = 0;
    }

  private:
    unsigned mId = 0;
    Deleter mDeleter = nullptr;
};

}  // namespace twinrender::realtime::gl
