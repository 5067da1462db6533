#include "cli_errors.hpp"

#include <exception>
#include <new>

#include "interrupt.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::app {

int run_reporting_errors(const std::function<int()>& body, std::ostream& err) {
  try {
    return body();
  } catch (const Interrupted& e) {
    err << "pgmcl: " << e.what() << "\n";
    return 128 + e.signal();
  } catch (const io::UsageError& e) {
    err << "pgmcl: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::bad_alloc&) {
    err << "pgmcl: error: out of memory (an input asks for more than this machine has)\n";
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
