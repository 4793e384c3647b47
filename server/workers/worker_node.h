// RunWorkerNode: the worker role of radfluxd (radfluxd --worker --server HOST:PORT). Dials
// the server's Worker service, announces its threads, and builds the row blocks it is
// leased: the scene is fetched by its hash and prepared (mesh + Embree) once per job, then
// each of its OpenMP threads builds one leased block at a time with BuildRowBlock, exactly
// as the server would, and the rows go back checksummed (block_wire.h); a heartbeat goes
// every second meanwhile. Reconnects after a lost connection; stops for good on
// UNAUTHENTICATED.
#pragma once

#include <atomic>
#include <string>

namespace radflux {

struct WorkerNodeOptions {
  std::string server;             // HOST:PORT of radfluxd
  int threads = 0;                // 0 = all cores
  std::string worker_token;       // sent as "authorization: Bearer <token>"
  std::string tls_ca;             // PEM CA file: connect with TLS (empty = plaintext)
  std::string tls_cert, tls_key;  // PEM client certificate and key, for a server that asks
                                  // for one (--tls-client-ca); empty = none
  std::string tls_server_name;    // overrides the name checked in the server certificate
  int block_delay_ms = 0;         // testing: sleep this long after building each block
};

// Runs until *stop is set (returns 0) or the server refuses the worker (returns 2).
int RunWorkerNode(const WorkerNodeOptions& options, const std::atomic<bool>& stop);

}  // namespace radflux
