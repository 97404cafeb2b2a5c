#pragma once
/// @file SampleBuffer.h
/// The samples of a ScalarField: a vector of floats that it owns, or floats that another owner
/// keeps (a NumPy array given to Python's octrace.Volume), read in place without a copy.
///
/// Reading never copies. Writing copies a borrowed buffer into one of its own first (copy on
/// write), so the other owner's memory is never changed: a caller that only reads should read
/// through a const reference (`std::as_const`), or a non-const operator[] makes the copy.
/// Copying a buffer copies owned samples and shares borrowed ones (the owner is kept alive by
/// every copy).
#include <cstddef>
#include <initializer_list>
#include <memory>
#include <span>
#include <vector>

namespace octrace {

class SampleBuffer {
public:
    SampleBuffer() = default;
    SampleBuffer(std::vector<float> samples) : owned_(std::move(samples)) {}  // NOLINT: a vector is samples
    SampleBuffer(std::initializer_list<float> samples) : owned_(samples) {}
    SampleBuffer& operator=(std::vector<float> samples) {
        owned_ = std::move(samples);
        release();
        return *this;
    }

    SampleBuffer& operator=(std::initializer_list<float> samples) { return *this = std::vector<float>(samples); }

    /// `count` floats at `data`, kept valid (and unchanged) by `owner` as long as any buffer
    /// sharing them lives. `owner` must not be null.
    static SampleBuffer borrow(const float* data, std::size_t count, std::shared_ptr<const void> owner) {
        SampleBuffer b;
        b.borrowed_ = data;
        b.count_ = count;
        b.owner_ = std::move(owner);
        return b;
    }
    /// True while the samples are another owner's (until the first write).
    bool borrowed() const { return owner_ != nullptr; }

    std::size_t size() const { return owner_ ? count_ : owned_.size(); }
    bool empty() const { return size() == 0; }
    const float* data() const { return owner_ ? borrowed_ : owned_.data(); }
    const float& operator[](std::size_t i) const { return data()[i]; }
    const float* begin() const { return data(); }
    const float* end() const { return data() + size(); }
    const float& front() const { return data()[0]; }
    const float& back() const { return data()[size() - 1]; }
    std::span<const float> span() const { return {data(), size()}; }
    operator std::span<const float>() const { return span(); }  // NOLINT: read as a span anywhere

    // Writing: a borrowed buffer becomes an owned copy first.
    float* data() { return vector().data(); }
    float& operator[](std::size_t i) { return vector()[i]; }
    float* begin() { return vector().data(); }
    float* end() { return vector().data() + owned_.size(); }
    float& front() { return vector().front(); }
    float& back() { return vector().back(); }
    void resize(std::size_t n) { vector().resize(n); }
    void resize(std::size_t n, float v) { vector().resize(n, v); }
    void assign(std::size_t n, float v) {
        release();
        owned_.assign(n, v);
    }
    template <class It>
    void assign(It first, It last) {
        std::vector<float> v(first, last);  // `first` may point into the borrowed samples
        *this = std::move(v);
    }
    void push_back(float v) { vector().push_back(v); }
    void reserve(std::size_t n) { vector().reserve(n); }
    std::size_t capacity() const { return owner_ ? count_ : owned_.capacity(); }
    void clear() {
        release();
        owned_.clear();
    }
    void shrink_to_fit() { vector().shrink_to_fit(); }
    /// The samples as a vector of this buffer's own (copied first when borrowed).
    std::vector<float>& vector() {
        if (owner_) {
            owned_.assign(borrowed_, borrowed_ + count_);
            release();
        }
        return owned_;
    }

    friend bool operator==(const SampleBuffer& a, const SampleBuffer& b) {
        if (a.size() != b.size()) return false;
        for (std::size_t i = 0; i < a.size(); ++i)
            if (!(a[i] == b[i])) return false;
        return true;
    }

private:
    void release() {
        owner_.reset();
        borrowed_ = nullptr;
        count_ = 0;
    }

    std::vector<float> owned_;
    const float* borrowed_ = nullptr;
    std::size_t count_ = 0;
    std::shared_ptr<const void> owner_;
};

}  // namespace octrace
