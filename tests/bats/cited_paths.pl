#!/usr/bin/perl
# cited_paths.pl ROOT: prints "FILE:LINE: WHAT" for every citation in a comment or a document of the
# tree at ROOT that does not resolve, and exits 1 if there is one (layout.bats).
#
# Read: every .md document whole; the comments of the sources (after // in C++, after # in shell,
# Bats, make, CMake, awk, Python, problem texts and dictionaries); the schemas' JSON whole. Cited:
#   - a repository path: a word starting with a top-level folder (tools/, templates/, scenarios/,
#     schemas/, tests/, prompts/, cmake/, .ci/) must exist; one followed by <, *, {, $, % or @ is a
#     pattern (scenarios/S<NN>/) and is not checked, nor is one with "..." in it or a folder
#     named in capitals ending in NN (scenarios/SNN/, the same placeholder);
#   - a bare document name NAME.md (no folder) must be the name of a file somewhere in the tree,
#     except the documents every run writes (report.md, scoreboard.md);
#   - a section, DOC "Section" or DOC, "Section" (DOC: README, a path or a NAME.md): DOC must have
#     a heading (#...) containing Section, or a paragraph opening with **Section. README is the
#     top-level README.md; a bare NAME.md is the one beside the citing file, else the only one.
use strict;
use warnings;

my $root = shift or die "usage: cited_paths.pl ROOT\n";
chdir $root or die "cannot enter $root\n";
my @files = split /\n/, `git ls-files --cached --others --exclude-standard`;
my %basenames;
for my $f (@files) { (my $b = $f) =~ s{.*/}{}; push @{ $basenames{$b} }, $f if -f $f; }
my %generated = map { $_ => 1 } qw(report.md scoreboard.md);
my $top = qr{(?:tools|templates|scenarios|schemas|tests|prompts|cmake|\.ci)/};
my $bad = 0;

sub complain { my ($where, $what) = @_; print "$where: $what\n"; $bad = 1; }

# The document a section citation names, or undef.
sub resolve_doc {
  my ($doc, $citing) = @_;
  return 'README.md' if $doc eq 'README';
  return -f $doc ? $doc : undef if $doc =~ m{/};
  (my $dir = $citing) =~ s{[^/]*$}{};
  return "$dir$doc" if -f "$dir$doc";
  my $all = $basenames{$doc} || [];
  return @$all == 1 ? $all->[0] : undef;
}

my %sections;
sub has_section {
  my ($doc, $section) = @_;
  unless ($sections{$doc}) {
    open my $fh, '<', $doc or return 0;
    my $fence = 0;
    while (<$fh>) {
      $fence = !$fence if /^```/;
      next if $fence;
      push @{ $sections{$doc} }, $1 if /^#+\s+(.*)/ || /^\*\*(.*)/;
    }
  }
  return grep { index($_, $section) >= 0 } @{ $sections{$doc} || [] };
}

for my $file (@files) {
  next unless -f $file;
  my $kind;
  if ($file =~ /\.md$/) { $kind = 'all' }
  elsif ($file =~ /\.(cpp|hpp|h|cc)$/) { $kind = 'slash' }
  elsif ($file =~ m{^schemas/.*\.json$}) { $kind = 'all' }
  elsif ($file =~ /\.(sh|bats|bash|mk|cmake|awk|py|dict|txt)$/ || $file =~ m{(^|/)(Makefile|CMakeLists\.txt|\.ci/run)$}) { $kind = 'hash' }
  else { next }
  open my $fh, '<', $file or next;
  while (my $line = <$fh>) {
    my $text;
    if ($kind eq 'all') { $text = $line }
    elsif ($kind eq 'slash') { next unless $line =~ m{//(.*)}; $text = $1 }
    else { next unless $line =~ /(?:^|\s)#(?!!)(.*)/; $text = $1 }
    my $where = "$file:$.";
    while ($text =~ m{(?<![\w./\$-])($top[\w.+/-]*)(.?)}g) {
      my ($path, $next) = ($1, $2);
      $path =~ s/[.,:;-]+$//;
      next if $next =~ /[<*{\$%@]/ || $path =~ /\.\.\./ || $path =~ m{/[A-Z]*NN(/|$)};
      complain($where, "no such path: $path") unless -e $path;
    }
    while ($text =~ m{(?<![\w./-])([\w-]+\.md)\b}g) {
      my $name = $1;
      complain($where, "no document named $name in the tree") unless $basenames{$name} || $generated{$name};
    }
    while ($text =~ m{(?<![\w./-])(README|[\w./-]+\.md)`?,? "([^"]+)"}g) {
      my ($doc, $section) = ($1, $2);
      my $target = resolve_doc($doc, $file);
      if (!defined $target) { complain($where, "$doc (cited for \"$section\") is not one document of the tree") }
      elsif (!has_section($target, $section)) { complain($where, "$target has no section \"$section\"") }
    }
  }
}
exit $bad;
