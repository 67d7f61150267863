#include "receiver/products/product_sink.hpp"

#include <exception>

namespace deepnav {

void finish_all(const std::vector<ProductSink*>& sinks, const NavData& decoded, std::vector<ProductFailure>& failures) {
  for (ProductSink* s : sinks) {
    try {
      s->finish(decoded);
    } catch (const std::exception& e) {
      failures.push_back({s->name(), e.what()});
    }
  }
}

}  // namespace deepnav
