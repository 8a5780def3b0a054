#pragma once
// A minimal XML well-formedness check for tests (tags nest and close, attributes are quoted,
// entities are known), and a count of elements by name. Not a validating parser.

#include <map>
#include <string>

namespace relplane::testing {

// False with "offset N: reason" when `text` is not a well-formed XML document with one root.
// `element_counts` (optional) receives how many elements of each name it holds.
bool CheckXml(const std::string& text, std::string* error,
              std::map<std::string, int>* element_counts = nullptr);

}  // namespace relplane::testing
