#include <cmath>

#include "diffray/cli/commands.h"

namespace diffray::cli {

void addRaysOption(CLI::App* sub, std::uint64_t& target, const std::string& help) {
  sub->add_option_function<double>(
         "--rays",
         [&target](double v) {
           if (!(v >= 1 && v <= 1e13 && std::floor(v) == v))
             throw CLI::ValidationError("--rays", "must be a whole number >= 1 (e.g. 2000000 or 2e6)");
           target = static_cast<std::uint64_t>(v);
         },
         help)
      ->type_name("N");
}

}  // namespace diffray::cli
