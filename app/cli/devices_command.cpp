// skein devices: say which CUDA devices answer
#include "subcommand.hpp"

#include <iostream>
#include <memory>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "cuda/device.hpp"

namespace skein::cli {
namespace {

struct DevicesCommand final : Subcommand {
  CLI::App* devices = nullptr;

  void declare(CLI::App& app) override {
    devices = app.add_subcommand("devices", "say which CUDA devices answer");
  }

  bool chosen() const override { return devices->parsed(); }

  int run(const Context&) override {
    const auto q = cuda::query_devices();
    std::cout << cuda::describe(q) << "\n";
    return 0;
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_devices_command() { return std::make_unique<DevicesCommand>(); }

}  // namespace skein::cli
