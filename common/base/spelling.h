// One spelling table per enum: the words by which input files, SID and result files name
// its values, read and written through the same table (so that a value has one spelling).
//
//   const Spelling<JointType> kJointTypes[] = {{"spherical", JointType::kSpherical}, ...};
//   spell(kJointTypes, JointType::kSpherical) == "spherical";
//   parseSpelling(kJointTypes, "spherical", &type) == true.
#pragma once

#include <cstddef>
#include <string_view>

namespace ffriga {

template <class E>
struct Spelling {
  const char* text;
  E value;
};

// The word for `value` ("?" for a value the table lacks: a programming error).
template <class E, std::size_t N>
const char* spell(const Spelling<E> (&table)[N], E value) {
  for (const Spelling<E>& s : table)
    if (s.value == value) return s.text;
  return "?";
}

// The value spelled `text`; false (and *value unchanged) for a word the table lacks.
template <class E, std::size_t N>
bool parseSpelling(const Spelling<E> (&table)[N], std::string_view text, E* value) {
  for (const Spelling<E>& s : table) {
    if (text == s.text) {
      *value = s.value;
      return true;
    }
  }
  return false;
}

}  // namespace ffriga
