// One registry type for every kind of pluggable component (sensor models, supernode engines,
// track associations, metrics): a name-ordered table of specs, looked up by the name the
// scenario gives, with the "unknown X 'y'; expected one of: ..." message written once.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace wsn::common {

/// `Spec` is any struct with a `std::string name` (and usually a description, a parameter table
/// and a factory). Entries keep registration order, which is the order `wsntrack components`
/// lists them in.
template <typename Spec>
class Registry {
 public:
  /// `kind` names the component in messages ("tracker engine", "sensor model").
  explicit Registry(std::string kind, std::vector<Spec> specs = {}) : kind_(std::move(kind)) {
    for (auto& spec : specs) add(std::move(spec));
  }

  /// Adds a component; a second component of the same name is a programming error.
  void add(Spec spec) {
    if (find(spec.name) != nullptr) throw std::logic_error(kind_ + " '" + spec.name + "' registered twice");
    specs_.push_back(std::move(spec));
  }

  /// The component called `name`, or nullptr.
  const Spec* find(const std::string& name) const {
    const auto it = std::find_if(specs_.begin(), specs_.end(), [&](const Spec& s) { return s.name == name; });
    return it == specs_.end() ? nullptr : &*it;
  }

  /// The component called `name`; throws Error("<prefix>unknown <kind> 'name'; expected one of: ...").
  template <typename Error = std::invalid_argument>
  const Spec& at(const std::string& name, const std::string& prefix = "") const {
    if (const Spec* spec = find(name)) return *spec;
    throw Error(prefix + "unknown " + kind_ + " '" + name + "'; expected one of: " + names());
  }

  /// "a, b, c": every name, in registration order.
  std::string names() const {
    std::string out;
    for (const auto& s : specs_) out += (out.empty() ? "" : ", ") + s.name;
    return out.empty() ? "(none)" : out;
  }

  const std::string& kind() const { return kind_; }
  const std::vector<Spec>& all() const { return specs_; }
  auto begin() const { return specs_.begin(); }
  auto end() const { return specs_.end(); }
  std::size_t size() const { return specs_.size(); }
  bool empty() const { return specs_.empty(); }
  const Spec& front() const { return specs_.front(); }

 private:
  std::string kind_;
  std::vector<Spec> specs_;
};

}  // namespace wsn::common
