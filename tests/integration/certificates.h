// Certificates for the mutual TLS tests, made with the openssl tool at test time.
#pragma once

#include <cstdlib>
#include <fstream>
#include <string>

namespace radflux::testing {

// Certificates made with the openssl tool in `dir` at test time (EC P-256, valid one day).
class Certificates {
 public:
  explicit Certificates(std::string dir) : dir_(std::move(dir)) {}
  // A self-signed CA `name`: files name.pem, name.key.
  bool MakeCa(const std::string& name) {
    return Run(
        "openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes "
        "-days 1 -subj /CN=" +
        name + " -keyout " + Key(name) + " -out " + Pem(name));
  }
  // A certificate `name` for `subject_alt_name` (e.g. "DNS:localhost"), signed by CA `ca`.
  bool MakeSigned(const std::string& name, const std::string& ca,
                  const std::string& subject_alt_name) {
    const std::string ext = dir_ + "/" + name + ".ext";
    std::ofstream(ext) << "subjectAltName=" << subject_alt_name << "\n";
    return Run("openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -subj /CN=" +
               name + " -keyout " + Key(name) + " -out " + dir_ + "/" + name + ".csr") &&
           Run("openssl x509 -req -days 1 -in " + dir_ + "/" + name + ".csr -CA " + Pem(ca) +
               " -CAkey " + Key(ca) + " -CAcreateserial -extfile " + ext + " -out " + Pem(name));
  }
  std::string Pem(const std::string& name) const { return dir_ + "/" + name + ".pem"; }
  std::string Key(const std::string& name) const { return dir_ + "/" + name + ".key"; }

 private:
  static bool Run(const std::string& command) {
    return std::system((command + " 2>/dev/null").c_str()) == 0;
  }
  std::string dir_;
};

}  // namespace radflux::testing
