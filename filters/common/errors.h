// The few exceptions a MeshRegrid core throws. Plugins turn them into
// MLException messages; the message always says what is wrong and what to do.
#pragma once

#include <stdexcept>
#include <string>

namespace mr {

/// The input cannot be processed as given (empty, no faces, NaN, bad parameter).
class InvalidInput : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// The input's connectivity does not allow the operation (e.g. non-manifold).
class TopologyError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// The algorithm could not finish (a front that does not close, ...).
class AlgorithmFailure : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace mr
