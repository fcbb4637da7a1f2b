// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/csv.hpp"

#include "common/errors.hpp"
#include "common/version.hpp"

namespace roifem::io {

CsvWriter::CsvWriter(const std::filesystem::path& path, const std::string& header) : file_(path), out_(file_.temporary_path()) {
  if (!out_) throw InputError(path.string() + ": cannot create file");
  out_ << "# roifem " << version() << '\n' << header << '\n';
}

void CsvWriter::row(const std::string& line) { out_ << line << '\n'; }

void CsvWriter::close() {
  out_.flush();
  if (!out_) throw InputError(file_.final_path().string() + ": write failed (disk full?)");
  out_.close();
  file_.commit();
}

}  // namespace roifem::io
