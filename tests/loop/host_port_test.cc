#include "loop/host_port.h"

#include <gtest/gtest.h>

#include "loop/socket_address.h"

namespace radfarm::loop {
namespace {

TEST(HostPortTest, ParsesIpv4NamesAndBracketedIpv6) {
  Result<HostPort> v4 = ParseHostPort("127.0.0.1:7000", "--listen");
  ASSERT_TRUE(v4.ok()) << v4.error();
  EXPECT_EQ(v4->host, "127.0.0.1");
  EXPECT_EQ(v4->port, 7000);

  Result<HostPort> v6 = ParseHostPort("[::1]:0", "--listen");
  ASSERT_TRUE(v6.ok()) << v6.error();
  EXPECT_EQ(v6->host, "::1");
  EXPECT_EQ(v6->port, 0);
  EXPECT_EQ(v6->ToString(), "[::1]:0");

  Result<HostPort> name = ParseHostPort("farm-master.local:65535", "--master");
  ASSERT_TRUE(name.ok()) << name.error();
  EXPECT_EQ(name->host, "farm-master.local");
  EXPECT_EQ(name->port, 65535);
}

TEST(HostPortTest, RejectsMalformedAddressesWithAClearMessage) {
  Result<HostPort> x = ParseHostPort("x", "--listen");
  ASSERT_FALSE(x.ok());
  EXPECT_EQ(x.error().rfind("--listen: expected HOST:PORT, got 'x'", 0), 0u) << x.error();

  for (const char* bad : {"", ":7000", "host:", "host:port", "host:65536", "host:-1", "host:+80",
                          "host:123456", "::1:7000", "[::1]7000", "[::1:7000", "[]:7000", "a b:80",
                          "host:80 ", "[::1]:", "1.2.3.4:0x50"}) {
    Result<HostPort> parsed = ParseHostPort(bad, "--listen");
    ASSERT_FALSE(parsed.ok()) << "'" << bad << "' was accepted";
    EXPECT_NE(parsed.error().find("--listen: expected HOST:PORT, got '" + std::string(bad) + "'"),
              std::string::npos)
        << parsed.error();
  }
  EXPECT_NE(ParseHostPort("::1:7000", "--listen").error().find("brackets"), std::string::npos);
}

TEST(SocketAddressTest, PrintsBothFamilies) {
  Result<SocketAddress> v4 = SocketAddress::FromIpLiteral({"127.0.0.1", 80});
  ASSERT_TRUE(v4.ok());
  EXPECT_EQ(v4->ToString(), "127.0.0.1:80");
  Result<SocketAddress> v6 = SocketAddress::FromIpLiteral({"::1", 7000});
  ASSERT_TRUE(v6.ok());
  EXPECT_EQ(v6->ToString(), "[::1]:7000");
  EXPECT_EQ(v6->port(), 7000);
  EXPECT_FALSE(SocketAddress::FromIpLiteral({"localhost", 80}).ok());
}

TEST(SocketAddressTest, ResolvesLiteralsWithoutLookupAndNamesWithOne) {
  Result<std::vector<SocketAddress>> literal = Resolve({"10.1.2.3", 9}, /*passive=*/false);
  ASSERT_TRUE(literal.ok()) << literal.error();
  EXPECT_EQ(literal->front().ToString(), "10.1.2.3:9");
  Result<std::vector<SocketAddress>> local = Resolve({"localhost", 9}, /*passive=*/false);
  ASSERT_TRUE(local.ok()) << local.error();
  EXPECT_EQ(local->front().port(), 9);
}

}  // namespace
}  // namespace radfarm::loop
