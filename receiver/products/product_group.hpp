#pragma once
// A run's products side by side, each on its own: one that throws (a full disk, a writer
// refusing a value) is abandoned at once — its partial file and an earlier run's file of
// the same name are removed, so on a full disk its space goes back to the others — then
// recorded, warned about, and no longer called, while the others go on to the end of the
// run and finish. The group's own calls never throw, so whatever drives the run (the
// receiver, a recorded fusion) finishes every product however many fail.
#include <functional>
#include <string>
#include <vector>

#include "receiver/products/product_sink.hpp"

namespace deepnav {

/// A product that could not be written, and why.
struct ProductFailure {
  std::string product;
  std::string error;
};

class ProductGroup final : public ProductSink {
 public:
  ProductGroup() = default;
  explicit ProductGroup(std::vector<ProductSink*> products);

  void on_epoch(const NavigationEpoch& e) override;
  void on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) override;
  /// Finishes the products in order; a product that fails here is recorded at once, so a
  /// later one (the run's summary, last) can report it.
  void finish(const NavData& decoded) override;
  void abandon() noexcept override;
  std::string name() const override { return "products"; }

  /// Runs `write` for `product` (one of the group's) outside the sink calls, e.g. from a
  /// trace callback, with the same isolation; nothing once the product has failed.
  void write_for(const ProductSink& product, const std::function<void()>& write);

  /// The products that failed, in the order they did.
  const std::vector<ProductFailure>& failures() const { return failures_; }
  /// "N of the products could not be written (the others are): a: why; b: why".
  std::string failure_message() const;

 private:
  template <class Call>
  void each(const Call& call);
  template <class Call>
  void guarded(std::size_t i, const Call& call);
  std::vector<ProductSink*> products_;
  std::vector<bool> failed_;
  std::vector<ProductFailure> failures_;
};

}  // namespace deepnav
