#include "receiver/products/product_group.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <exception>
#include <stdexcept>

namespace deepnav {

ProductGroup::ProductGroup(std::vector<ProductSink*> products)
    : products_(std::move(products)), failed_(products_.size(), false) {}

template <class Call>
void ProductGroup::guarded(std::size_t i, const Call& call) {
  if (failed_[i]) return;
  try {
    call();
  } catch (const std::exception& e) {
    failed_[i] = true;
    products_[i]->abandon();
    failures_.push_back({products_[i]->name(), e.what()});
    spdlog::warn("{}: {}: this product is left out, the others go on", products_[i]->name(), e.what());
  }
}

template <class Call>
void ProductGroup::each(const Call& call) {
  for (std::size_t i = 0; i < products_.size(); ++i) guarded(i, [&] { call(*products_[i]); });
}

void ProductGroup::on_epoch(const NavigationEpoch& e) {
  each([&](ProductSink& p) { p.on_epoch(e); });
}

void ProductGroup::on_correlation(const CorrelatorEpoch& e, const ChannelSnapshot& ch) {
  each([&](ProductSink& p) { p.on_correlation(e, ch); });
}

void ProductGroup::finish(const NavData& decoded) {
  each([&](ProductSink& p) { p.finish(decoded); });
}

void ProductGroup::abandon() noexcept {
  for (std::size_t i = 0; i < products_.size(); ++i)
    if (!failed_[i]) products_[i]->abandon();
}

void ProductGroup::write_for(const ProductSink& product, const std::function<void()>& write) {
  for (std::size_t i = 0; i < products_.size(); ++i)
    if (products_[i] == &product) return guarded(i, write);
  throw std::logic_error("ProductGroup::write_for: '" + product.name() + "' is not one of the group's products");
}

std::string ProductGroup::failure_message() const {
  std::string what;
  for (const ProductFailure& f : failures_) what += (what.empty() ? "" : "; ") + f.product + ": " + f.error;
  return fmt::format("{} of the products could not be written (the others are): {}", failures_.size(), what);
}

}  // namespace deepnav
