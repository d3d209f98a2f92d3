// Runs a core call and turns the cores' typed exceptions into MLException,
// the one error type MeshLab and PyMeshLab show to users.
#pragma once

#include <common/mlexception.h>

#include "common/errors.h"

#include <new>
#include <utility>

namespace mr::bridge {

template <class Call>
auto run_core(const char* filter, Call&& call) -> decltype(call()) {
  const QString prefix = QString("%1: ").arg(filter);
  try {
    return std::forward<Call>(call)();
  } catch (const mr::InvalidInput& e) {
    throw MLException(prefix + e.what());
  } catch (const mr::TopologyError& e) {
    throw MLException(prefix + e.what());
  } catch (const mr::AlgorithmFailure& e) {
    throw MLException(prefix + e.what());
  } catch (const std::bad_alloc&) {
    throw MLException(prefix + "out of memory");
  } catch (const MLException&) {
    throw;
  } catch (const std::exception& e) {
    throw MLException(prefix + "internal error: " + e.what());
  }
}

}  // namespace mr::bridge
