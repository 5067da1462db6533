#include "cli_errors.hpp"

#include <exception>
#include <new>

#include "pgmcl/io/values.hpp"

namespace pgmcl::app {

int run_reporting_errors(const std::function<int()>& body, std::ostream& err) {
  try {
    return body();
  } catch (const io::UsageError& e) {
    err << "pgmcl: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::bad_alloc&) {
    err << "pgmcl: error: out of memory\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    err << "pgmcl: error: " << e.what() << "\n";
    return kExitFailure;
  } catch (...) {
    err << "pgmcl: error: unknown exception\n";
    return kExitFailure;
  }
}

}  // namespace pgmcl::app
