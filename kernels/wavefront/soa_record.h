// A structure-of-arrays record generated from its field list, so that a work item's fields are
// written once (work_items.h) and its storage, allocation and size follow from them.
// FIELDS(X) lists the fields as X(type, name); SNEE_SOA_RECORD(Name, FIELDS) declares
//   struct Name {
//     explicit Name(size_t capacity);     // every array padded_capacity(capacity) entries
//     AlignedArray<type> name; ...         // one array per field, indexed by queue position
//     static constexpr size_t bytes_per_entry();
//   };
#pragma once

#include <cstddef>

#include "kernels/wavefront/aligned_array.h"

// A 3-vector field `name` as three float arrays name_x, name_y, name_z.
#define SNEE_SOA_VECTOR(X, name) X(float, name##_x) X(float, name##_y) X(float, name##_z)

#define SNEE_SOA_DECLARE(type, name) AlignedArray<type> name;
#define SNEE_SOA_ALLOCATE(type, name) name = AlignedArray<type>(entries);
#define SNEE_SOA_BYTES(type, name) +sizeof(type)

#define SNEE_SOA_RECORD(Name, FIELDS)                                              \
  struct Name {                                                                    \
    explicit Name(size_t capacity) {                                               \
      [[maybe_unused]] const size_t entries = padded_capacity(capacity);           \
      FIELDS(SNEE_SOA_ALLOCATE)                                                    \
    }                                                                              \
    FIELDS(SNEE_SOA_DECLARE)                                                       \
    static constexpr size_t bytes_per_entry() { return 0 FIELDS(SNEE_SOA_BYTES); } \
  }
